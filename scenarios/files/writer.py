"""Scenario -> scenario file (TOML, format 1): what `mbxval export --format toml` writes.

Every number is written with Python's shortest round-tripping repr, so reading the file back gives
the very same floats, and the native solver gives bit-identical results. Keys whose value is the
vocabulary's default are left out.
"""

from __future__ import annotations

import dataclasses
import json
import math
from typing import Any

from scenarios.bodies import Body, Point
from scenarios.files.schema import FORMAT, MOTIONS, PROFILES, SECTIONS, Kind, kind_name
from scenarios.scenario import LEVELS, Scenario, ScenarioError, characteristic_rate


def toml_value(value: Any) -> str:
    """One value in TOML syntax: numbers exactly, tuples as arrays, dicts as inline tables."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, tuple | list):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{ " + ", ".join(f"{k} = {toml_value(v)}" for k, v in value.items()) + " }"
    raise TypeError(f"cannot write {type(value).__name__} to a scenario file")


def _kinds_of(value: object) -> dict[str, Kind] | None:
    for kinds in (MOTIONS, PROFILES):
        if any(type(value) is k.cls for k in kinds.values()):
            return kinds
    return None


def _plain(value: Any) -> Any:
    """A vocabulary value as TOML-ready data: points, motions and profiles become tables."""
    if isinstance(value, Point):
        return {"body": value.body, "local": tuple(float(c) for c in value.local)}
    kinds = _kinds_of(value)
    if kinds is not None:
        return {"kind": kind_name(value, kinds), **_fields(value)}
    if isinstance(value, tuple):
        return tuple(_plain(v) for v in value)
    return value


def _fields(obj: Any) -> dict[str, Any]:
    """The fields of a vocabulary object that differ from their defaults, as TOML-ready data."""
    out: dict[str, Any] = {}
    for field in dataclasses.fields(obj):
        value = getattr(obj, field.name)
        if (
            field.default is not dataclasses.MISSING
            and value == field.default
            and type(value) is type(field.default)
        ):
            continue
        out[field.name] = _plain(value)
    return out


def _table(header: str, values: dict[str, Any]) -> list[str]:
    return ["", f"[[{header}]]", *(f"{k} = {toml_value(v)}" for k, v in values.items())]


def _body(body: Body) -> dict[str, Any]:
    return {"name": body.name, **{k: v for k, v in _fields(body).items() if k != "name"}}


WRITTEN = frozenset(
    {"family", "variant", "description", "t_end", "steps", "characteristic_length", "outputs", "levels"}
    | {"characteristic_rate", "bodies", "joints", "drivers", "forces", "gravity", "analysis"}
    | {"angle_outputs"}
)
"""The Scenario fields format 1 holds. Any other field with a value off its default is refused, so
that a file never silently drops part of a scenario."""


NAME_TAGS = frozenset({"point"})
"""Scenario fields that only tag a scenario's name (a swept point's overrides), not its mechanism: a
file of a swept point is written from the family with --set instead, so the writer refuses them."""
ORIGIN = frozenset({"parameters"})
"""Scenario fields that say where a mechanism came from (a family's parameter values), not what it
is: a file is the mechanism, so they are not written (the rate they give is: characteristic_rate)."""


def read_back(scenario: Scenario) -> Scenario:
    """The scenario its file reads back as: the same mechanism, grid and scales (its rate declared),
    without the ORIGIN fields a file does not hold."""
    return dataclasses.replace(scenario, parameters=(), characteristic_rate=characteristic_rate(scenario))


def _default(field: dataclasses.Field[Any]) -> Any:
    if field.default_factory is not dataclasses.MISSING:
        return field.default_factory()
    return field.default


def _refuse_unwritten(scenario: Scenario) -> None:
    for field in dataclasses.fields(scenario):
        if field.name not in WRITTEN | ORIGIN and getattr(scenario, field.name) != _default(field):
            raise ScenarioError(
                f"{scenario.name}: scenario files (format {FORMAT}) cannot hold {field.name} yet"
            )


def scenario_toml(scenario: Scenario) -> str:
    """The scenario file text that reads back as `scenario`."""
    _refuse_unwritten(scenario)
    lines = [
        "# mbxval scenario file (see docs/scenario-files.md)",
        f"format = {FORMAT}",
        f"name = {toml_value(scenario.family)}",
    ]
    if scenario.variant != "default":
        lines.append(f"variant = {toml_value(scenario.variant)}")
    if scenario.description:
        lines.append(f"description = {toml_value(scenario.description)}")
    lines += [
        f"t_end = {toml_value(float(scenario.t_end))}",
        f"steps = {int(scenario.steps)}",
        f"characteristic_length = {toml_value(float(scenario.characteristic_length))}",
        f"characteristic_rate = {toml_value(float(characteristic_rate(scenario)))}",
    ]
    if scenario.outputs:
        lines.append(f"outputs = {toml_value(scenario.outputs)}")
    if scenario.levels != LEVELS:
        lines.append(f"levels = {toml_value(scenario.levels)}")
    if any(g != 0.0 or math.copysign(1.0, g) < 0.0 for g in scenario.gravity):  # -0.0 kept too
        lines.append(f"gravity = {toml_value(tuple(float(g) for g in scenario.gravity))}")
    if scenario.analysis != "kinematic":
        lines.append(f"analysis = {toml_value(scenario.analysis)}")
    for body in scenario.bodies:
        lines += _table("bodies", _body(body))
    sections = (("joints", scenario.joints), ("drivers", scenario.drivers), ("forces", scenario.forces))
    for section, items in sections:
        for item in items:
            values = _fields(item)
            lines += _table(
                section, {"kind": kind_name(item, SECTIONS[section]), "name": values.pop("name"), **values}
            )
    for output in scenario.angle_outputs:
        lines += _table("angle_outputs", _fields(output))
    return "\n".join(lines) + "\n"
