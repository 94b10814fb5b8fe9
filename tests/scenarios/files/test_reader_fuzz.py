"""A property of the scenario-file reader: whatever a TOML document holds, reading it (and loading
it as a file, with `--set` values) either gives a Scenario or raises one ScenarioError whose message
is one line naming the file; never another exception.

The documents are built-in scenarios written out (valid structure), then edited by Hypothesis:
values replaced by TOML values of any type (numbers at and past their ranges, strings, arrays,
tables), keys deleted, keys added (known and unknown), `kind`s switched, and `--set` paths drawn
from the document's own and random. Text is drawn without control or line-break characters: a
name holding one is refused where names enter, which its own tests cover."""

from __future__ import annotations

import json
import math
import tempfile
import tomllib
from pathlib import Path
from typing import Any

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import scenarios
from scenarios.files import parse_scenario, scenario_toml
from scenarios.files.schema import BODY_KEYS, MOTIONS, PROFILES, SECTIONS, TOP_LEVEL
from scenarios.scenario import ScenarioError

BASES = {
    name: tomllib.loads(scenario_toml(scenarios.build(name)))
    for name in ("slider_crank", "cam_roller/spline", "spur_gears", "compound_pendulum", "andrews_squeezer")
}
KINDS = sorted({*MOTIONS, *PROFILES, *(k for kinds in SECTIONS.values() for k in kinds)})
KEYS = sorted(
    {
        *TOP_LEVEL,
        *BODY_KEYS,
        "kind",
        "csv",
        *(key for kinds in (MOTIONS, PROFILES, *SECTIONS.values()) for k in kinds.values() for key in k.keys),
    }
)
TEXT = st.text(st.characters(blacklist_categories=("Cc", "Cs", "Zl", "Zp")), max_size=12)
"""Text as a user types it, of any script (control and line-break characters aside)."""
EDGE_NUMBERS = (0, -1, 1, 2**31, -(2**63), 2**63 - 1, 0.0, -0.0, 1e-300, 1e300, math.inf, -math.inf, math.nan)
SCALARS = st.one_of(
    st.sampled_from(EDGE_NUMBERS),
    st.integers(-(2**63), 2**63 - 1),
    st.floats(allow_nan=True, allow_infinity=True),
    st.booleans(),
    TEXT,
    st.sampled_from([*KINDS, "ground", "crank", "rod", "position", "velocity", "dynamic"]),
)
VALUES = st.recursive(
    SCALARS,
    lambda inner: (
        st.lists(inner, max_size=4) | st.dictionaries(st.sampled_from(KEYS) | TEXT, inner, max_size=4)
    ),
    max_leaves=10,
)


def toml_text(value: Any) -> str:
    """A value in TOML syntax, keys quoted, tables inline (a writer for any key, unlike the
    scenario writer's)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return "nan" if math.isnan(value) else repr(value)
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False).replace("\x7f", "\\u007f")
    if isinstance(value, list):
        return "[" + ", ".join(map(toml_text, value)) + "]"
    return "{" + ", ".join(f"{toml_text(str(k))} = {toml_text(v)}" for k, v in value.items()) + "}"


def document(doc: dict[str, Any]) -> str:
    return "".join(f"{toml_text(key)} = {toml_text(value)}\n" for key, value in doc.items())


@st.composite
def edited(draw: st.DrawFn) -> tuple[dict[str, Any], list[str]]:
    """A built-in scenario's document with a few edits, each at a place drawn from all of its
    places alike (a joint's `kind` as likely as a body's mass), and the `--set` paths of the result."""
    doc = json.loads(json.dumps(BASES[draw(st.sampled_from(sorted(BASES)))]))  # a deep copy
    for _ in range(draw(st.integers(1, 4))):
        path = draw(st.sampled_from([(), *places(doc)]))
        parent: Any = doc
        for key in path[:-1]:
            parent = parent[key]
        action = draw(st.sampled_from(["replace", "delete", "add", "kind"]))
        if not path or action == "add":
            node = parent[path[-1]] if path and isinstance(parent[path[-1]], dict | list) else parent
            if isinstance(node, dict):
                node[draw(st.sampled_from(KEYS) | TEXT)] = draw(VALUES)
            else:
                node.append(draw(VALUES))
        elif action == "delete":
            del parent[path[-1]]
        elif action == "kind" and isinstance(parent, dict):
            parent["kind"] = draw(st.sampled_from(KINDS))
        else:
            parent[path[-1]] = draw(VALUES)
    return doc, [".".join(map(str, path)) for path in places(doc)]


def places(node: Any) -> list[tuple[str | int, ...]]:
    """The key path of every value in the document (arrays by index), outer before inner."""
    items = node.items() if isinstance(node, dict) else enumerate(node) if isinstance(node, list) else ()
    found: list[tuple[str | int, ...]] = []
    for key, value in items:
        found += [(key,), *((key, *inner) for inner in places(value))]
    return found


@st.composite
def overrides(draw: st.DrawFn, paths: list[str]) -> dict[str, str]:
    """`--set` values: paths of the document or random ones, values as TOML text or any text."""
    keys = st.sampled_from(paths) | TEXT.filter(bool)
    values = VALUES.map(toml_text) | TEXT
    return draw(st.dictionaries(keys, values, max_size=3))


def assert_read_or_refused(text: str, sets: dict[str, str]) -> None:
    try:
        parse_scenario(text, "fuzz.toml", overrides=sets)
    except ScenarioError as error:
        message = str(error)
        assert len(message.splitlines()) == 1 and message.startswith("fuzz.toml: "), message


FUZZ = settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])


@FUZZ
@given(st.data())
def test_an_edited_document_is_read_or_refused_in_one_line(data: st.DataObject) -> None:
    doc, paths = data.draw(edited())
    assert_read_or_refused(document(doc), data.draw(overrides(paths)))


@settings(max_examples=100, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.data())
def test_an_edited_file_loads_or_is_refused_in_one_line(data: st.DataObject) -> None:
    """The same through scenarios.load, as every command and the API read a file (its grid and end
    time checked after it is read)."""
    doc, paths = data.draw(edited())
    sets = data.draw(overrides(paths))
    with tempfile.TemporaryDirectory() as folder:
        file = Path(folder) / "fuzz.toml"
        file.write_text(document(doc), encoding="utf-8")
        try:
            scenarios.load(str(file), sets)
        except ScenarioError as error:
            message = str(error)
            assert len(message.splitlines()) == 1 and message.startswith(str(file)), message


def test_the_property_sees_both_outcomes() -> None:
    """It cannot pass by refusing everything: each base, written back as the fuzz writes it, reads."""
    for doc in BASES.values():
        assert isinstance(parse_scenario(document(doc), "fuzz.toml"), scenarios.Scenario)
    bad = {**BASES["slider_crank"], "steps": 0.5}
    try:
        parse_scenario(document(bad), "fuzz.toml")
    except ScenarioError as error:
        assert str(error).startswith("fuzz.toml: steps: expected an integer")
    else:
        raise AssertionError("a float step count was read")
