"""The scenario file format as a JSON Schema (draft 2020-12), derived from the declarations in
scenarios.files.schema and the vocabulary classes' required fields, so that editors complete and
check files (`mbxval schema > scenario.schema.json`; for TOML, Taplo and Even Better TOML read a
`#:schema scenario.schema.json` line). The reader stays the judge: what a schema cannot say (a body
named in a point exists, a vector is not zero, cross-key checks such as eccentricity below radius)
it checks alone, so a file the schema accepts may still be refused, never the other way round.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from scenarios.bodies import GROUND, Body
from scenarios.files import schema as declared
from scenarios.files.reader import required_keys
from scenarios.files.schema import Key, Kind
from scenarios.names import MAX_NAME_LENGTH
from scenarios.outputs import AngleOutput
from scenarios.scenario import LEVELS

Schema = dict[str, Any]
DRAFT = "https://json-schema.org/draft/2020-12/schema"
NAME_PATTERN = r"^[^\x00-\x1f\x7f]*\S[^\x00-\x1f\x7f]*$"
"""A name as an editor can check it: not blank, no ASCII control character (the reader refuses
more: scenarios.names)."""
NUMBER_RANGES: dict[str, Schema] = {
    "finite": {},
    "positive": {"exclusiveMinimum": 0},
    "nonnegative": {"minimum": 0},
}


def _numbers(key: Key, size: int | None) -> Schema:
    schema: Schema = {"type": "array", "items": {"type": "number"}}
    if size is not None:
        schema.update(minItems=size, maxItems=size)
    elif key.minimum_length:
        schema["minItems"] = key.minimum_length
    return schema


def key_schema(key: Key) -> Schema:
    """The schema of one declared key, with its meaning where it declares one."""
    schema = _typed(key)
    return {**schema, "description": key.doc} if key.doc else schema


def _typed(key: Key) -> Schema:
    kind = key.type
    if kind == "number":
        return {"type": "number", **NUMBER_RANGES[key.range]}
    if kind == "integer":
        return {"type": "integer", **({"minimum": 1} if key.range == "positive" else {})}
    if kind in ("string", "boolean"):
        return {"type": kind}
    if kind == "name":
        return {"type": "string", "minLength": 1, "maxLength": MAX_NAME_LENGTH, "pattern": NAME_PATTERN}
    if kind == "choice":
        return {"enum": list(key.choices)}
    if kind == "body":
        return {"type": "string", "description": f"a body of the file, or '{GROUND}'"}
    if kind == "moving_body":
        return {"type": "string", "not": {"const": GROUND}, "description": "a body of the file"}
    if kind in ("vec2", "pose", "numbers"):
        return _numbers(key, {"vec2": 2, "pose": 3}.get(kind))
    if kind == "strings":
        return {"type": "array", "items": {"type": "string"}, "uniqueItems": True}
    if kind == "levels":
        return {"type": "array", "items": {"enum": list(LEVELS)}, "minItems": 1, "uniqueItems": True}
    if kind == "parameters":
        return {"type": "object", "additionalProperties": {"type": ["number", "string"]}}
    if kind in ("point", "motion", "profile"):
        return {"$ref": f"#/$defs/{kind}"}
    raise AssertionError(kind)


def table(keys: Mapping[str, Key], required: tuple[str, ...]) -> Schema:
    """A table of declared keys, the required ones required and no other key allowed."""
    schema: Schema = {
        "type": "object",
        "properties": {name: key_schema(key) for name, key in keys.items()},
        "additionalProperties": False,
    }
    if required:
        schema["required"] = list(required)
    return schema


def kinds(options: Mapping[str, Kind]) -> Schema:
    """A table whose `kind` key selects one of `options`, each with its own keys."""
    cases = []
    for name, spec in options.items():
        keys = {"kind": Key("choice", choices=(name,)), **spec.keys}
        then = table(keys, ("kind", *required_keys(spec.cls)))
        if name == "spline":  # the radii inline, or from a CSV file beside the scenario file
            then["properties"][declared.SPLINE_CSV_KEY] = {
                "type": "string",
                "description": "CSV file of radii",
            }
            then["required"] = ["kind"]
            then["oneOf"] = [{"required": ["table"]}, {"required": [declared.SPLINE_CSV_KEY]}]
        cases.append({"if": {"properties": {"kind": {"const": name}}}, "then": then})
    return {
        "type": "object",
        "properties": {"kind": {"enum": list(options)}},
        "required": ["kind"],
        "allOf": cases,
    }


def _array(items: Schema, minimum: int = 0) -> Schema:
    return {"type": "array", "items": items, **({"minItems": minimum} if minimum else {})}


def scenario_schema() -> Schema:
    """The JSON Schema of a scenario file (of the format schema.FORMAT), as a JSON-ready dict."""
    top = table(
        {k: v for k, v in declared.TOP_LEVEL.items() if v.type != "tables"}, declared.TOP_LEVEL_REQUIRED
    )
    top["properties"]["format"] = {"const": declared.FORMAT}
    top["properties"].update(
        bodies=_array(
            table(declared.BODY_KEYS, required_keys(Body)), declared.TOP_LEVEL["bodies"].minimum_length
        ),
        angle_outputs=_array(table(declared.ANGLE_OUTPUT_KEYS, required_keys(AngleOutput))),
        **{section: _array(kinds(options)) for section, options in declared.SECTIONS.items()},
    )
    return {
        "$schema": DRAFT,
        "title": "mbxval scenario file",
        "description": f"A planar mechanism for mbxval, scenario file format {declared.FORMAT} "
        "(docs/scenario-files.md).",
        **top,
        "$defs": {
            "point": table(declared.POINT_KEYS, ("body",)),
            "motion": kinds(declared.MOTIONS),
            "profile": kinds(declared.PROFILES),
        },
    }
