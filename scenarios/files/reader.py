"""Scenario file (TOML) -> Scenario, checking every key against the schema.

Every problem is one ScenarioFileError whose message names the file, the key path (such as
`joints[2].p_i.body`) and what is wrong; nothing is built from a file with a problem.
"""

from __future__ import annotations

import dataclasses
import tomllib
from collections.abc import Mapping
from pathlib import Path
from typing import Any, NoReturn

from scenarios.bodies import GROUND, Body, Point
from scenarios.files.bounded_read import (
    MAX_PROFILE_CSV_BYTES,
    MAX_SCENARIO_FILE_BYTES,
    FileRefused,
    inside,
    read_bounded_text,
)
from scenarios.files.overrides import apply_overrides
from scenarios.files.profile_csv import read_radii
from scenarios.files.schema import (
    ANGLE_OUTPUT_KEYS,
    BODY_KEYS,
    FORMAT,
    KIND,
    MOTIONS,
    POINT_KEYS,
    PROFILES,
    SECTIONS,
    SPLINE_CSV_KEY,
    TOP_LEVEL,
    TOP_LEVEL_REQUIRED,
    Key,
    Kind,
    in_range,
    suggestion,
)
from scenarios.names import NameRefused, check_name, check_scenario_name
from scenarios.outputs import AngleOutput
from scenarios.scenario import LEVELS, Scenario, ScenarioError


class ScenarioFileError(ScenarioError):
    """A scenario file that cannot be read: the message is `FILE: KEY.PATH: what is wrong`."""


def toml_type(value: object) -> str:
    """The TOML name of a parsed value's type, for messages."""
    names = {bool: "boolean", int: "integer", float: "float", str: "string", list: "array", dict: "table"}
    return names.get(type(value), type(value).__name__)


def required_keys(cls: type) -> tuple[str, ...]:
    """The fields of a vocabulary class without a default: the keys a table must give."""
    return tuple(
        f.name
        for f in dataclasses.fields(cls)
        if f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING
    )


class Reader:
    """Reads one file's tables; `source` names the file in messages, `directory` anchors CSV paths."""

    def __init__(self, source: str, directory: Path) -> None:
        self.source = source
        self.directory = directory
        self.bodies: tuple[str, ...] = ()

    def fail(self, path: str, message: str) -> NoReturn:
        raise ScenarioFileError(f"{self.source}: {path}: {message}" if path else f"{self.source}: {message}")

    def keys(
        self, raw: object, keys: Mapping[str, Key], required: tuple[str, ...], path: str
    ) -> dict[str, Any]:
        """A table's values, converted; unknown and missing keys are errors."""
        if not isinstance(raw, dict):
            self.fail(path, f"expected a table, got {toml_type(raw)}")
        for name in raw:
            if name not in keys:
                known = list(keys)
                self.fail(
                    join(path, name), f"unknown key{suggestion(name, known)}; known keys: {', '.join(known)}"
                )
        for name in required:
            if name not in raw:
                self.fail(join(path, name), "missing")
        return {name: self.value(value, keys[name], join(path, name)) for name, value in raw.items()}

    def value(self, raw: object, key: Key, path: str) -> Any:
        """One value of a declared type, converted to what the vocabulary holds."""
        kind = key.type
        if kind == "number":
            return self.number(raw, key.range, path)
        if kind == "integer":
            if type(raw) is not int:
                self.fail(path, f"expected an integer, got {_shown(raw)}")
            if not in_range(raw, key.range):
                self.fail(path, f"must be {key.range}, got {raw!r}")
            return raw
        if kind in ("string", "choice", "body", "moving_body"):
            return self.text(raw, key, path)
        if kind == "name":
            return self.name(raw, path)
        if kind == "boolean":
            if type(raw) is not bool:
                self.fail(path, f"expected true or false, got {_shown(raw)}")
            return raw
        if kind in ("vec2", "pose", "numbers"):
            return self.numbers(raw, key, path)
        if kind in ("strings", "levels"):
            return self.strings(raw, kind, path)
        if kind == "point":
            values = self.keys(raw, POINT_KEYS, ("body",), path)
            return Point(**values)
        if kind == "motion":
            return self.kind(raw, MOTIONS, path)
        if kind == "profile":
            return self.kind(raw, PROFILES, path)
        if kind == "parameters":
            return self.parameters(raw, path)
        raise AssertionError(kind)

    def number(self, raw: object, range_: str, path: str) -> float:
        if type(raw) not in (int, float):
            self.fail(path, f"expected a number, got {_shown(raw)}")
        value = float(raw)  # type: ignore[arg-type]
        if not in_range(value, range_):
            self.fail(
                path,
                f"must be a {range_} number, got {raw!r}"
                if range_ != "finite"
                else f"must be finite, got {raw!r}",
            )
        return value

    def text(self, raw: object, key: Key, path: str) -> str:
        if not isinstance(raw, str):
            self.fail(path, f"expected a string, got {_shown(raw)}")
        choices: tuple[str, ...] = key.choices
        if key.type in ("body", "moving_body"):
            choices = self.bodies + ((GROUND,) if key.type == "body" else ())
            if raw == GROUND and GROUND not in choices:
                self.fail(path, f"'{GROUND}' is not a moving body; bodies: {', '.join(self.bodies)}")
            if raw not in choices:
                self.fail(
                    path,
                    f"unknown body{suggestion(raw, list(choices))}; bodies: {', '.join(self.bodies)}",
                )
        elif choices and raw not in choices:
            self.fail(
                path,
                f"unknown value{suggestion(raw, list(choices))}; expected one of {', '.join(choices)}",
            )
        return raw

    def name(self, raw: object, path: str) -> str:
        """A name (scenarios.names.check_name): refused without quoting it."""
        try:
            return check_name(raw, "a name")
        except NameRefused as refused:
            self.fail(path, str(refused))

    def scenario_name(self, raw: str, path: str) -> str:
        """The scenario's own name or variant: refused as `export --name` refuses it."""
        try:
            return check_scenario_name(raw, "the scenario's name")
        except NameRefused as refused:
            self.fail(path, str(refused))

    def numbers(self, raw: object, key: Key, path: str) -> tuple[float, ...]:
        size = {"vec2": 2, "pose": 3}.get(key.type)
        if not isinstance(raw, list):
            self.fail(path, f"expected an array of numbers, got {_shown(raw)}")
        if size is not None and len(raw) != size:
            self.fail(path, f"expected {size} numbers, got {len(raw)}")
        if len(raw) < key.minimum_length:
            self.fail(path, f"expected at least {key.minimum_length} numbers, got {len(raw)}")
        if len(raw) > MAX_NUMBERS:
            self.fail(path, f"{len(raw)} numbers, more than the {MAX_NUMBERS} an array may hold")
        values = tuple(self.number(v, "finite", f"{path}[{k}]") for k, v in enumerate(raw))
        if key.range == "nonzero" and not any(values):
            self.fail(path, "must not be the zero vector")
        return values

    def strings(self, raw: object, kind: str, path: str) -> tuple[str, ...]:
        if not isinstance(raw, list) or not all(isinstance(v, str) for v in raw):
            self.fail(path, f"expected an array of strings, got {_shown(raw)}")
        choices = LEVELS if kind == "levels" else self.bodies
        what = "level" if kind == "levels" else "body"
        for k, name in enumerate(raw):
            if name not in choices:
                self.fail(
                    f"{path}[{k}]",
                    f"unknown {what}{suggestion(name, list(choices))}; known: {', '.join(choices)}",
                )
        if len(set(raw)) != len(raw):
            self.fail(path, "lists a name twice")
        if kind == "levels" and not raw:
            self.fail(path, "must name at least one level")
        return tuple(raw)

    def parameters(self, raw: object, path: str) -> tuple[tuple[str, float | int | str], ...]:
        if not isinstance(raw, dict):
            self.fail(path, f"expected a table, got {toml_type(raw)}")
        for name, value in raw.items():
            self.name(name, path)
            if type(value) not in (int, float, str):
                self.fail(join(path, name), f"expected a number or a string, got {toml_type(value)}")
        return tuple(raw.items())

    def kind(self, raw: object, kinds: Mapping[str, Kind], path: str) -> Any:
        """A table whose `kind` key selects the vocabulary class it describes."""
        if not isinstance(raw, dict):
            self.fail(path, f"expected a table, got {toml_type(raw)}")
        if "kind" not in raw:
            self.fail(join(path, "kind"), f"missing; one of {', '.join(kinds)}")
        name = self.text(raw["kind"], KIND, join(path, "kind"))  # a string before it is looked up
        if name not in kinds:
            self.fail(
                join(path, "kind"),
                f"unknown kind{suggestion(str(name), list(kinds))}; known: {', '.join(kinds)}",
            )
        spec = kinds[name]
        body = {k: v for k, v in raw.items() if k != "kind"}
        if name == "spline" and SPLINE_CSV_KEY in body:
            body["table"] = self.csv_table(body.pop(SPLINE_CSV_KEY), join(path, SPLINE_CSV_KEY))
        values = self.keys(body, spec.keys, required_keys(spec.cls), path)
        problem = spec.check(values) if spec.check else None
        if problem is not None:
            self.fail(join(path, problem[0]), problem[1])
        return spec.cls(**values)

    def csv_table(self, raw: object, path: str) -> list[float]:
        """A spline profile's radii from a CSV file named relative to the scenario file."""
        if not isinstance(raw, str):
            self.fail(path, f"expected a file path, got {toml_type(raw)}")
        try:
            file = inside(self.directory, raw)
            return read_radii(read_bounded_text(file, MAX_PROFILE_CSV_BYTES, "profile CSV"), str(file))
        except OSError as error:
            self.fail(path, f"cannot read the file it names: {error.strerror or error}")
        except ValueError as error:  # FileRefused among them
            self.fail(path, str(error))


def _shown(raw: object) -> str:
    """A value's TOML type, and the value itself only when it is a number: a message never quotes
    a file's text."""
    if type(raw) in (int, float):
        return f"{toml_type(raw)} {raw!r}"
    return toml_type(raw)


def join(path: str, key: str) -> str:
    return f"{path}.{key}" if path else key


MAX_NUMBERS = 100_000
"""The most numbers in one array (a spline's knots, a tabulated law's samples)."""
MAX_TABLES = {"bodies": 2000, "joints": 4000, "drivers": 2000, "forces": 4000, "angle_outputs": 2000}
"""The most elements a scenario file's section may hold (a mechanism of 2,000 bodies is far past any
textbook linkage; the limits keep a hostile file from planning for minutes)."""
MIN_TABLES = {"bodies": 1}


def _named_tables(reader: Reader, raw: object, path: str) -> list[dict[str, Any]]:
    if not isinstance(raw, list) or not all(isinstance(t, dict) for t in raw):
        reader.fail(path, f"expected an array of tables ([[{path}]]), got {toml_type(raw)}")
    most, least = MAX_TABLES.get(path, 2000), MIN_TABLES.get(path, 0)
    if not least <= len(raw) <= most:
        reader.fail(path, f"{len(raw)} tables; a scenario file holds {least} to {most} [[{path}]]")
    return raw


def _bodies(reader: Reader, raw: object) -> tuple[Body, ...]:
    bodies: list[Body] = []
    for k, table in enumerate(_named_tables(reader, raw, "bodies")):
        values = reader.keys(table, BODY_KEYS, required_keys(Body), f"bodies[{k}]")
        if values["name"] == GROUND or values["name"] in (b.name for b in bodies):
            reader.fail(f"bodies[{k}].name", f"already taken, by another body or the {GROUND}")
        bodies.append(Body(**values))
    return tuple(bodies)


def _angle_outputs(reader: Reader, raw: object) -> tuple[AngleOutput, ...]:
    outputs: list[AngleOutput] = []
    for k, table in enumerate(_named_tables(reader, raw, "angle_outputs")):
        values = reader.keys(table, ANGLE_OUTPUT_KEYS, required_keys(AngleOutput), f"angle_outputs[{k}]")
        if values["name"] in (a.name for a in outputs):
            reader.fail(f"angle_outputs[{k}].name", "already taken by another angle output")
        outputs.append(AngleOutput(**values))
    return tuple(outputs)


def _constraints(reader: Reader, doc: dict[str, Any], section: str, taken: set[str]) -> tuple[Any, ...]:
    built = []
    for k, table in enumerate(_named_tables(reader, doc.get(section, []), section)):
        item = reader.kind(table, SECTIONS[section], f"{section}[{k}]")
        if item.name in taken:
            reader.fail(f"{section}[{k}].name", "names another constraint or force already")
        taken.add(item.name)
        built.append(item)
    return tuple(built)


def parse_scenario(
    text: str,
    source: str = "<string>",
    directory: Path = Path("."),
    overrides: Mapping[str, object] | None = None,
) -> Scenario:
    """The scenario a file's text describes, with `overrides` (dotted key path -> value) applied."""
    reader = Reader(source, directory)
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        reader.fail("", f"not valid TOML: {error}")
    except RecursionError:
        reader.fail("", "not read: its tables or arrays are nested too deeply")
    apply_overrides(doc, overrides or {}, reader.fail)
    version = doc.get("format")
    if type(version) is int and version > FORMAT:
        reader.fail("format", f"format {version} is newer than this mbxval reads (format {FORMAT})")
    if "format" in doc and version != FORMAT:
        reader.fail("format", f"expected format = {FORMAT}, got {version!r}")
    tables = ("bodies", "joints", "drivers", "forces", "angle_outputs", "outputs", "levels")
    structure = {k: v for k, v in doc.items() if k not in tables}
    top = reader.keys(structure, TOP_LEVEL, (), "")
    for key in ("name", "variant"):  # the loader must not read the name as a variant, file or point
        if key in top:
            reader.scenario_name(top[key], key)
    for name in TOP_LEVEL_REQUIRED:
        if name not in doc:
            reader.fail(name, "missing")
    bodies = _bodies(reader, doc["bodies"])
    reader.bodies = tuple(b.name for b in bodies)
    taken: set[str] = set()
    joints = _constraints(reader, doc, "joints", taken)
    drivers = _constraints(reader, doc, "drivers", taken)
    forces = _constraints(reader, doc, "forces", taken)
    return Scenario(
        family=top["name"],
        variant=top.get("variant", "default"),
        bodies=bodies,
        joints=joints,
        drivers=drivers,
        t_end=top["t_end"],
        steps=top["steps"],
        characteristic_length=top["characteristic_length"],
        characteristic_rate=top.get("characteristic_rate"),
        outputs=reader.value(doc.get("outputs", []), TOP_LEVEL["outputs"], "outputs"),
        levels=reader.value(doc.get("levels", list(LEVELS)), TOP_LEVEL["levels"], "levels"),
        parameters=top.get("parameters", ()),
        description=top.get("description", ""),
        gravity=top.get("gravity", (0.0, 0.0)),
        forces=forces,
        analysis=top.get("analysis", "kinematic"),
        angle_outputs=_angle_outputs(reader, doc.get("angle_outputs", [])),
    )


def read_scenario(path: str | Path, overrides: Mapping[str, object] | None = None) -> Scenario:
    """The scenario in the file at `path`; ScenarioFileError naming the file and key otherwise."""
    file = Path(path)
    try:
        text = read_bounded_text(file, MAX_SCENARIO_FILE_BYTES, "scenario file")
    except FileRefused as error:
        raise ScenarioFileError(str(error)) from None
    except OSError as error:
        raise ScenarioFileError(f"{file}: cannot read: {error.strerror or error}") from None
    return parse_scenario(text, str(file), file.parent, overrides)
