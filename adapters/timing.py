"""Run time as the minimum over repeats after untimed warm-ups: the one way mbxval times anything
(engine runs, benchmarks), because the minimum is the least disturbed by a shared, noisy machine.
Time is the process's CPU time (`time.process_time`: every thread of the process, an engine's own
threads included), the same clock for every engine, so that the figure measures the work and not
the load of the moment; the wall-clock time is measured beside it (`Instant`, `Timing.best_wall`).
A warm-up is the action itself unless a cheaper call that pays the same first-call costs is given
(an engine run's warm-up simulates the grid's first interval only, adapters.base). What the
timing itself cost is measured too (`timed`): the warm-up's seconds and the timed calls' summed,
so that the work a run does is a measured figure, not the minimum times the number of calls."""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Generic, TypeVar

T = TypeVar("T")

CPU_CLOCK = "process CPU time"
"""What the figures of `timed` measure, as a report names it."""


@dataclass(frozen=True)
class Instant:
    """A moment on both clocks: the process's CPU seconds and the wall clock's."""

    cpu: float
    wall: float

    def __sub__(self, earlier: Instant) -> Instant:
        return Instant(self.cpu - earlier.cpu, self.wall - earlier.wall)

    def __add__(self, other: Instant) -> Instant:
        return Instant(self.cpu + other.cpu, self.wall + other.wall)


ZERO = Instant(0.0, 0.0)


def now() -> Instant:
    """The process's CPU time and the wall clock, read together."""
    return Instant(time.process_time(), time.perf_counter())


@dataclass(frozen=True)
class Timing(Generic[T]):
    """What timing an action measured: its time per call and its last call's result, and what
    the timing spent (every call measured, none estimated); CPU seconds, wall seconds beside."""

    best: float
    """CPU seconds per call: the minimum over the timed repeats."""
    result: T
    """The last call's result."""
    repeats: int
    """Timed repeats made (fewer than asked where the first took longer than `once_above`, or
    where a repeat agreed with the best before it within `agree`)."""
    repeats_time: float
    """CPU seconds of all timed repeats, summed (`best` is their minimum, per call)."""
    warmup_time: float
    """CPU seconds of the untimed warm-up calls, summed (0 without a warm-up)."""
    best_wall: float = math.nan
    """Wall seconds per call: the minimum over the same repeats."""
    repeats_time_wall: float = math.nan
    """Wall seconds of all timed repeats, summed."""
    warmup_time_wall: float = math.nan
    """Wall seconds of the untimed warm-up calls, summed."""


def timed(
    action: Callable[[], T],
    repeats: int = 1,
    warmup: int = 0,
    number: int = 1,
    once_above: float = math.inf,
    warm: Callable[[], object] | None = None,
    agree: float = 0.0,
    budget: float = math.inf,
) -> Timing[T]:
    """`warmup` untimed calls of `warm` (by default the action itself), then the minimum over
    `repeats` (at least one) of the CPU time of `number` calls, divided by `number`; a first timed
    call longer than `once_above` CPU seconds is the only one (its noise is small against its
    length), and the repeats stop early where one agrees with the best before it to a relative
    `agree` (two undisturbed repeats: the minimum is known to that fraction, and more would only
    cost time; where they disagree the repeats go on), or where one more repeat as long as the
    best would take the repeats' CPU seconds past `budget` (as timeit's autorange bounds its
    loops: short actions are repeated, long ones are not; the repeats cost at most the larger of
    `budget` and one repeat). The warm-up's and the repeats' seconds are summed as they run, on
    both clocks."""
    start = now()
    for _ in range(warmup):
        (action if warm is None else warm)()
    warmed = now() - start
    best, best_wall, total, made = math.inf, math.inf, ZERO, 0
    result: T
    for _ in range(max(1, repeats)):
        start = now()
        for _ in range(max(1, number)):
            result = action()
        spent = now() - start
        per_call = spent.cpu / max(1, number)
        total, made = total + spent, made + 1
        done = enough(per_call, best, once_above, agree) or over_budget(
            total.cpu, min(best, per_call), number, budget
        )
        best, best_wall = min(best, per_call), min(best_wall, spent.wall / max(1, number))
        if done:
            break
    return Timing(best, result, made, total.cpu, warmed.cpu, best_wall, total.wall, warmed.wall)


def enough(latest: float, best_before: float, once_above: float, agree: float) -> bool:
    """Whether `timed` stops after a repeat of `latest` seconds, the best before it `best_before`
    (infinite before the first): where the best is over `once_above`, or where `latest` agrees
    with the best before it to a relative `agree` (never where `agree` is 0)."""
    agreed = agree > 0 and abs(latest - best_before) <= agree * min(latest, best_before)
    return min(latest, best_before) > once_above or agreed


def over_budget(spent: float, best: float, number: int, budget: float) -> bool:
    """Whether one more repeat of `number` calls, each as long as the best so far, would take the
    repeats' `spent` CPU seconds past `budget`."""
    return spent + best * max(1, number) > budget


def fastest(
    action: Callable[[], T],
    repeats: int = 1,
    warmup: int = 0,
    number: int = 1,
    warm: Callable[[], object] | None = None,
) -> tuple[float, T]:
    """(CPU seconds per call, the last call's result) of `timed` with the same arguments: every
    repeat made (the short cuts, `once_above` and `agree`, are the harness's, for engine runs)."""
    timing = timed(action, repeats, warmup, number, warm=warm)
    return timing.best, timing.result
