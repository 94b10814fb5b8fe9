"""Run time as the minimum over repeats after untimed warm-ups: the one way mbxval times anything
(engine runs, benchmarks), because the minimum is the least disturbed by a shared, noisy machine.
A warm-up is the action itself unless a cheaper call that pays the same first-call costs is given
(an engine run's warm-up simulates the grid's first interval only, adapters.base)."""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from typing import TypeVar

T = TypeVar("T")


def fastest(
    action: Callable[[], T],
    repeats: int = 1,
    warmup: int = 0,
    number: int = 1,
    once_above: float = math.inf,
    warm: Callable[[], object] | None = None,
) -> tuple[float, T]:
    """(seconds per call, the last call's result): `warmup` untimed calls of `warm` (by default the
    action itself), then the minimum over `repeats` (at least one) of the time of `number` calls,
    divided by `number`; a first timed call longer than `once_above` seconds is the only one (its
    noise is small against its length)."""
    for _ in range(warmup):
        (action if warm is None else warm)()
    best = math.inf
    result: T
    for _ in range(max(1, repeats)):
        start = time.perf_counter()
        for _ in range(max(1, number)):
            result = action()
        best = min(best, (time.perf_counter() - start) / max(1, number))
        if best > once_above:
            break
    return best, result
