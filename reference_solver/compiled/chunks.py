"""The grid marched in chunks of about CHUNK_SECONDS of compiled work each: a compiled call runs to
its end whatever signal comes, so the interpreter, and with it a SIGTERM's or Ctrl-C's handler, runs
between two calls. A chunk is sized from the estimated cost of one grid point (scenarios.limits'
costs for dense solves, KERNEL_ROW_STEP_SECONDS for the banded kernel)."""

from __future__ import annotations

from collections.abc import Iterator

from scenarios.limits import DENSE_STEP_SECONDS

CHUNK_SECONDS = 0.1
"""The compiled work between two chances for a signal's handler to run."""
KERNEL_ROW_STEP_SECONDS = 0.5e-6
"""CPU time of the compiled kinematic kernel per constraint row and grid point (its Newton steps on
the banded rows), an upper estimate from a 3-body slider-crank to a 2001-body chain."""
SOLVE_ROW_STEP_SECONDS = 2e-6
"""CPU time of the compiled inverse dynamics per constraint row and grid point beside its dense
least-squares solve (the rows, the loads, the solve's set-up)."""


def banded_point_seconds(rows: int) -> float:
    """Estimated seconds of one grid point of the kinematic kernel on `rows` constraint rows."""
    return rows * KERNEL_ROW_STEP_SECONDS


def dense_point_seconds(rows: int) -> float:
    """Estimated seconds of one grid point of a dense least-squares solve of `rows` rows."""
    return rows * SOLVE_ROW_STEP_SECONDS + DENSE_STEP_SECONDS * float(rows) ** 3


def chunks(count: int, point_seconds: float) -> Iterator[tuple[int, int]]:
    """(start, stop) of consecutive chunks covering range(count), each of about CHUNK_SECONDS at
    `point_seconds` a point, at least one point each."""
    size = max(1, int(CHUNK_SECONDS / max(point_seconds, 1e-12)))
    for start in range(0, count, size):
        yield start, min(start + size, count)
