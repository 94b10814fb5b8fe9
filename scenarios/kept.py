"""Per-scenario results kept for the last few scenarios, for work a harness repeats for every run of
a scenario's group (the native solver compiling its program or building its constraint system, the
harness digesting the scenario for each row). It needs nothing but the scenario, so the solver and
the harness share it from here without one importing the other."""

from __future__ import annotations

from collections.abc import Callable
from functools import lru_cache
from typing import TypeVar

from scenarios.scenario import Scenario

T = TypeVar("T")


def kept(maxsize: int) -> Callable[[Callable[[Scenario], T]], Callable[[Scenario], T]]:
    """`build(scenario)`, kept for the last `maxsize` scenarios; a scenario that cannot be hashed
    (say, a list where the vocabulary has a tuple) is built each time, not kept."""

    def wrap(build: Callable[[Scenario], T]) -> Callable[[Scenario], T]:
        cached = lru_cache(maxsize=maxsize)(build)

        def get(scenario: Scenario) -> T:
            try:
                hash(scenario)
            except TypeError:
                return build(scenario)
            return cached(scenario)

        get.__doc__ = build.__doc__
        get.cache_info = cached.cache_info  # type: ignore[attr-defined]
        return get

    return wrap
