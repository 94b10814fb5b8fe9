"""One way to name a scenario everywhere: a built-in name (`family` or `family/variant`) or the
path of a scenario file (`*.toml`), either with the parameter values of a swept point in brackets
(`four_bar[crank_length=0.08,omega=50]`, scenarios.scenario.point_name)."""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping

from scenarios.files import read_scenario
from scenarios.limits import check_grid, check_t_end
from scenarios.registry import build
from scenarios.scenario import POINT_RESERVED, Scenario, ScenarioError


def is_scenario_file(name: str) -> bool:
    """Whether `name` names a scenario file rather than a built-in scenario."""
    return split_point(name)[0].endswith(".toml")


def split_point(name: str) -> tuple[str, dict[str, str]]:
    """The base name and the overrides of a swept point's name; a plain name has none."""
    if not name.endswith("]") or "[" not in name:
        return name, {}
    base, _, inner = name[:-1].partition("[")
    overrides: dict[str, str] = {}
    for item in inner.split(","):
        key, sep, value = item.partition("=")
        if not sep or not key or not value or any(c in POINT_RESERVED for c in key + value):
            raise ScenarioError(f"'{name}' is not a swept point's name: expected {base}[NAME=VALUE,...]")
        overrides[key] = value
    return base, overrides


def load(name_or_path: str, overrides: Mapping[str, str] | None = None) -> Scenario:
    """The scenario a name or a file describes. `overrides` set family parameters by name, or a
    file's values by dotted key path (`bodies.crank.mass`); a swept point's own values come first."""
    base, point = split_point(name_or_path)
    values = {**point, **(overrides or {})}
    if base.endswith(".toml"):
        scenario = read_scenario(base, values)
        check_t_end(scenario.name, scenario.t_end)
        check_grid(scenario.name, scenario.steps + 1, len(scenario.bodies))
    else:
        scenario = build(base, overrides=values)  # checks the same bounds
    return dataclasses.replace(scenario, point=tuple(point.items())) if point else scenario
