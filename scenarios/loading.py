"""One way to name a scenario everywhere: a built-in name (`family` or `family/variant`) or the
path of a scenario file (`*.toml`), either with the parameter values of a swept point in brackets
(`four_bar[crank_length=0.08,omega=50]`, scenarios.scenario.point_name)."""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping

from scenarios.family import MAX_GRID_STEPS
from scenarios.files import read_scenario
from scenarios.limits import check_grid, check_t_end, dense
from scenarios.names import check_name
from scenarios.registry import build, family
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
        key = check_name(key, "a swept point's parameter")
        overrides[key] = check_name(value, f"the value of {key}")
    return base, overrides


def load(name_or_path: str, overrides: Mapping[str, str] | None = None) -> Scenario:
    """The scenario a name or a file describes. `overrides` set family parameters by name, or a
    file's values by dotted key path (`bodies.crank.mass`); a swept point's own values come first."""
    base, point = split_point(name_or_path)
    values = {**point, **(overrides or {})}
    if base.endswith(".toml"):
        scenario = read_scenario(base, values)
        check_t_end(scenario.name, scenario.t_end)
        check_grid(scenario.name, scenario.steps + 1, len(scenario.bodies), dense(scenario))
    else:
        values, grid = _grid_keys(base, values)
        scenario = _with_grid(build(base, overrides=values), grid)  # build checks the same bounds
    return dataclasses.replace(scenario, point=tuple(point.items())) if point else scenario


GRID_KEYS = ("t_end", "steps")
"""The time grid's keys, which every scenario takes: a file and a family that declares them set
them itself; for another family `t_end` replaces the end its parameters give (turns over a speed,
periods) and `steps` its number of equal steps, so that `run --t-end/--steps` and the bracket form
`slider_crank[t_end=0.5]` mean the same for every scenario."""


def _grid_keys(base: str, values: dict[str, str]) -> tuple[dict[str, str], dict[str, str]]:
    """The family's own parameters, and the grid keys it does not declare."""
    declared = family(base.split("/", 1)[0]).parameters
    grid = {k: v for k, v in values.items() if k in GRID_KEYS and k not in declared}
    return {k: v for k, v in values.items() if k not in grid}, grid


def _with_grid(scenario: Scenario, grid: Mapping[str, str]) -> Scenario:
    """`scenario` on the grid the undeclared grid keys give, each checked (ScenarioError)."""
    if not grid:
        return scenario
    name, t_end, steps = scenario.name, scenario.t_end, scenario.steps
    try:
        t_end = float(grid.get("t_end", t_end))
        steps = int(grid.get("steps", steps))
    except ValueError as error:
        raise ScenarioError(f"{name}: t_end must be a number and steps a whole number: {error}") from None
    if not 1 <= steps <= MAX_GRID_STEPS:
        raise ScenarioError(f"{name}: steps must be in [1, {MAX_GRID_STEPS}], got {steps}")
    check_t_end(name, t_end)
    check_grid(name, steps + 1, len(scenario.bodies), dense(scenario))
    return dataclasses.replace(scenario, t_end=t_end, steps=steps)
