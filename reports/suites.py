"""Named suites: which scenarios to run, over which settings, how often, with which time limit.

A suite is registered once with `register`; `mbxval run --suite NAME` and `mbxval check` find it
here. Variants named `stress...` belong to a stress suite, never to the default one.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from scenarios import catalogue


@dataclass(frozen=True)
class Suite:
    """`scenarios()` names the scenarios; `sweep` False runs each engine's default setting only."""

    name: str
    description: str
    scenarios: Callable[[], list[str]]
    sweep: bool = True
    repeats: int = 3
    warmup: int = 1
    timeout: float = 60.0


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
        "every family's default and main variants; every engine over its sweep",
        main_scenarios,
    )
)
register(
    Suite(
        "quick",
        "the default suite's scenarios at each engine's default setting only, timed once (for `check`)",
        main_scenarios,
        sweep=False,
        repeats=1,
        warmup=0,
    )
)
