"""Named suites: which scenarios to run, over which settings, how often, with which time limit.

A suite is registered once with `register`; `mbxval run --suite NAME` and `mbxval check` find it
here. Variants named `stress...` belong to the stress suite, never to the default one.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from reports.dynamics import cases as dynamics_cases
from scenarios import catalogue

if TYPE_CHECKING:
    from adapters.base import Adapter, Setting
    from reports.scoring import NamedTruth
    from scenarios.scenario import Scenario
    from scenarios.trajectory import Trajectory


@dataclass(frozen=True)
class Suite:
    """`scenarios()` names the scenarios; `ladder` False runs each engine's default setting only.

    `truth(scenario, times)` replaces the runner's reference truth; `settings(scenario, adapter)`
    gives a scenario's settings for an engine (the first one its default), or None for the engine's
    own default and ladder.
    """

    name: str
    description: str
    scenarios: Callable[[], list[str]]
    ladder: bool = True
    repeats: int = 3
    warmup: int = 1
    timeout: float = 60.0
    truth: Callable[[Scenario, Any], Trajectory | NamedTruth] | None = None
    settings: Callable[[Scenario, Adapter], list[Setting] | None] | None = None


SUITES: dict[str, Suite] = {}


def register(suite: Suite) -> Suite:
    SUITES[suite.name] = suite
    return suite


def get(name: str) -> Suite:
    """The suite called `name`; KeyError naming the known ones otherwise."""
    if name not in SUITES:
        raise KeyError(f"unknown suite '{name}'; known: {', '.join(SUITES)}")
    return SUITES[name]


def is_stress(name: str) -> bool:
    return name.partition("/")[2].startswith("stress")


def main_scenarios() -> list[str]:
    """Every family's default and named variants, stress variants excepted."""
    return [name for name in catalogue() if not is_stress(name)]


register(
    Suite(
        "default",
        "every family's default and main variants; every engine over its ladder",
        main_scenarios,
    )
)
register(
    Suite(
        "quick",
        "the default suite's scenarios at each engine's default setting only, timed once (for `check`)",
        main_scenarios,
        ladder=False,
        repeats=1,
        warmup=0,
    )
)


def stress_scenarios() -> list[str]:
    """The stress cases (reports.stress.cases): every stress variant the catalogue has, declared,
    and the nominal scenarios they are compared with."""
    from reports.stress import scenario_names

    return scenario_names()


def _stress_truth(scenario: Scenario, times: Any) -> NamedTruth:
    from reports.scoring import NamedTruth
    from reports.stress import stress_truth, stress_truth_name

    return NamedTruth(stress_truth(scenario, times), stress_truth_name(scenario))


def _stress_settings(scenario: Scenario, adapter: Adapter) -> list[Setting] | None:
    from reports.stress import stress_settings

    return stress_settings(scenario, adapter)


register(
    Suite(
        "stress",
        "singular, extreme and long cases: where each engine breaks, and how (the stability map)",
        stress_scenarios,
        ladder=False,
        repeats=1,
        warmup=0,
        timeout=120.0,  # the long horizon's MuJoCo run takes 15-40 s on 2 loaded cores
        truth=_stress_truth,
        settings=_stress_settings,
    )
)


register(
    Suite(
        "dynamics",
        "forward dynamics against the native truth: every dynamic scenario over each engine's ladder, "
        "and the stiffness-step stability map",
        dynamics_cases.scenario_names,
        timeout=300.0,
        truth=dynamics_cases.truth,
        settings=dynamics_cases.settings,
    )
)
