"""scenarios.kept: a build kept for the last `maxsize` scenarios, least recently used out
first, and an unhashable scenario built each time. The decorator is applied here, inside the tests
(the solver's and the harness's own uses are decorated at import, before any test runs)."""

from __future__ import annotations

import dataclasses
from collections.abc import Callable

import scenarios
from scenarios.kept import kept
from scenarios.scenario import Scenario


def counted(maxsize: int) -> tuple[list[Scenario], Callable[[Scenario], tuple[str, int]]]:
    """A build that records each scenario it is given and returns (its name, its step count), kept."""
    built: list[Scenario] = []

    def build(scenario: Scenario) -> tuple[str, int]:
        """The scenario's name and steps."""
        built.append(scenario)
        return scenario.name, len(scenario.times())

    return built, kept(maxsize)(build)


def four_bars(count: int) -> list[Scenario]:
    return [scenarios.build("four_bar", overrides={"steps": 10 + k}) for k in range(count)]


def test_a_scenario_is_built_once_while_it_is_among_the_last_maxsize() -> None:
    built, get = counted(2)
    a, b, c = four_bars(3)
    assert [get(s) for s in (a, b, a, b)] == [(a.name, 11), (b.name, 12), (a.name, 11), (b.name, 12)]
    assert built == [a, b]
    get(c)  # b, then a least recently used: a goes
    assert get(b) == (b.name, 12) and built == [a, b, c]
    get(a)
    assert built == [a, b, c, a]
    info = get.cache_info()  # type: ignore[attr-defined]
    assert (info.hits, info.misses, info.maxsize, info.currsize) == (3, 4, 2, 2)
    assert get.__doc__ == "The scenario's name and steps."  # type: ignore[attr-defined]


def test_an_unhashable_scenario_is_built_each_time_and_not_kept() -> None:
    built, get = counted(4)
    (scenario,) = four_bars(1)
    unhashable = dataclasses.replace(scenario, parameters=[("note", 1.0)])  # type: ignore[arg-type]
    assert get(unhashable) == get(unhashable) == (scenario.name, 11)
    assert len(built) == 2 and all(s is unhashable for s in built)
    assert get.cache_info().currsize == 0  # type: ignore[attr-defined]
