"""What the dynamics suite runs: every dynamic scenario, the stiffness-step map and the truth.

- `scenario_names()`: every dynamic family's default and variants (the families declare
  `dynamic=True`), the stiff spring's map cells (`stiff_spring/k..._dt...`) included;
- the truth: the native forward dynamics at TRUTH_RTOL, except in scenarios that pass through a
  singular configuration (SINGULAR_PASSAGES), where DOP853 cannot reach that tolerance in reasonable
  time (the dependent coordinates' round-off is amplified there) and the truth is at the looser
  tolerance given; the native engine is then run no tighter than JUDGED_MARGIN times that, so the
  truth is always far tighter than what it judges (a fixed-step setting, ALI3-P's default through
  singular passages, runs as it is);
- the map cells run each engine's modes with the cell's output step as their step `dt` (the default
  mode first: the map shows it), the other scenarios each engine's ladder.
"""

from __future__ import annotations

from typing import Any

from adapters import NATIVE
from adapters.base import Adapter, Setting
from adapters.step_rule import at_step
from reports.scoring import DYNAMIC_RTOL, NamedTruth
from scenarios import catalogue
from scenarios.families.stiff_spring import MAP_VARIANTS
from scenarios.registry import all_families
from scenarios.scenario import Scenario

TRUTH_RTOL = DYNAMIC_RTOL
PASSAGE_RTOL = 1e-12
SINGULAR_PASSAGES = {name: PASSAGE_RTOL for name, f in all_families().items() if f.singular_passages}
"""Families whose motion passes a singular configuration (they declare it: Family.singular_passages),
and the truth's tolerance there."""
JUDGED_MARGIN = 10.0
MAP_FAMILY = "stiff_spring"
LEFT_OUT = ("n_four_bar/spec",)
"""Too long for a suite every engine runs (81 bodies over 20 s): run it by name."""


def scenario_names() -> list[str]:
    """Every dynamic scenario of the catalogue, LEFT_OUT excepted."""
    return [n for n in catalogue(include_dynamic=True) if is_dynamic(n) and n not in LEFT_OUT]


def is_dynamic(name: str) -> bool:
    """Whether `name` is a scenario of a dynamic family."""
    family = all_families().get(name.partition("/")[0])
    return family is not None and family.dynamic


def map_cells() -> dict[str, dict[str, float]]:
    """The stiffness-step map's scenario names and their (stiffness, dt)."""
    return {f"{MAP_FAMILY}/{name}": values for name, values in MAP_VARIANTS.items()}


def truth_rtol(scenario: Scenario) -> float:
    return SINGULAR_PASSAGES.get(scenario.family, TRUTH_RTOL)


def truth(scenario: Scenario, times: Any) -> NamedTruth:
    """The native forward dynamics at the scenario's truth tolerance, on the compiled constraints
    (reference_solver.compiled_system); on the plain ones through a singular passage, where
    round-off picks the outcome (at rtol 1e-12 n_four_bar holds its energy to 1.4e-9 of the kinetic
    energy on the plain path, 7e-9 on the compiled one, 2e-8 of the length apart; 0.53 on the
    compiled one before Newton started from each accepted step), and the native engine's default,
    the compiled path, is judged by the other one."""
    from reference_solver.dynamics import simulate  # on first use: the native solver is slow to import

    rtol = truth_rtol(scenario)
    compiled = scenario.family not in SINGULAR_PASSAGES
    path = "" if compiled else ", plain constraints"
    trajectory = simulate(scenario, times, rtol, compiled=compiled).trajectory()
    return NamedTruth(trajectory, f"native dynamics, DOP853 rtol {rtol:g}{path}")


def settings(scenario: Scenario, adapter: Adapter) -> list[Setting] | None:
    """The suite's settings hook (reports.suites): a map cell runs each engine's modes at the
    cell's step; the native engine, whose forward dynamics is the truth, runs no
    tighter than JUDGED_MARGIN times the truth's tolerance; otherwise each engine's own ladder."""
    if scenario.name in map_cells():
        return _at_step(scenario, adapter)
    if adapter.name == NATIVE and scenario.analysis == "dynamic":
        loosest = truth_rtol(scenario) * JUDGED_MARGIN
        chosen = [adapter.default_setting(scenario), *adapter.ladder(scenario)]
        return _unique([_no_tighter(s, loosest) for s in chosen])
    return None


def _no_tighter(setting: Setting, loosest: float) -> Setting:
    """`setting` with its tolerance `rtol` at least `loosest`; a fixed-step setting as it is."""
    if setting.get("rtol") is None:
        return setting
    return setting.replace(rtol=max(float(setting["rtol"]), loosest))


def _at_step(scenario: Scenario, adapter: Adapter) -> list[Setting]:
    """Each of the engine's modes (its default's first) at the cell's output step, for the modes
    that take a step `dt`; the engine's default where it takes none."""
    step = scenario.t_end / scenario.steps
    default = adapter.default_setting(scenario)
    firsts: dict[str, Setting] = {}
    for setting in (default, *adapter.ladder(scenario)):
        firsts.setdefault(setting.mode, setting)
    stepped = [at_step(s, step) for s in firsts.values() if s.get("dt") is not None]
    return _unique(stepped) if stepped and stepped[0].mode == default.mode else [default]


def _unique(settings: list[Setting]) -> list[Setting]:
    return list(dict.fromkeys(settings))
