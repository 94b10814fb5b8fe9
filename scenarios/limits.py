"""The documented bounds every scenario input is checked against where it enters, before anything
is built or allocated, so that a typo (`loops=1e30`, `steps=inf`, `crank_length=1e308`) is one
clear refusal naming the limit, never a kernel OOM kill or a traceback deep in the solver.

- every number is finite; a real parameter (a length, an angle, a rate, a ratio) is at most
  MAX_MAGNITUDE in size, in its SI unit;
- a count (loops, knots, lobes, ...) is at most MAX_COUNT; the grid's `steps` at most MAX_STEPS;
- the end time is at most MAX_T_END seconds;
- a trajectory (grid points x bodies x 3 coordinates x 3 levels, 8 bytes each) is at most
  MAX_TRAJECTORY_BYTES (2 GiB), estimated before the grid is allocated.
"""

from __future__ import annotations

import math

from scenarios.scenario import ParameterValue, ScenarioError

MAX_MAGNITUDE = 1e6
MAX_COUNT = 10_000
MAX_STEPS = 10_000_000
MAX_T_END = 1e6  # seconds
MAX_TRAJECTORY_BYTES = 2 * 1024**3
GRID_PARAMETERS = ("steps",)


def check_parameter(family: str, key: str, value: ParameterValue) -> None:
    """Refuse a typed parameter value outside its bound (ScenarioError naming the bound)."""
    if isinstance(value, str | bool):
        return
    if not math.isfinite(value):
        raise ScenarioError(f"{family}: parameter {key} must be a finite number, got {value}")
    if isinstance(value, int):
        bound = MAX_STEPS if key in GRID_PARAMETERS else MAX_COUNT
        if abs(value) > bound:
            raise ScenarioError(f"{family}: parameter {key} must be at most {bound} in size, got {value:.6g}")
    elif abs(value) > MAX_MAGNITUDE:
        raise ScenarioError(
            f"{family}: parameter {key} must be at most {MAX_MAGNITUDE:g} in size (SI units), got {value:g}"
        )


def check_t_end(name: str, t_end: float) -> None:
    if not (math.isfinite(t_end) and 0 < t_end <= MAX_T_END):
        raise ScenarioError(f"{name}: the end time must be positive and at most {MAX_T_END:g} s, got {t_end:g}")


def trajectory_bytes(points: float, bodies: int) -> float:
    """Memory of a trajectory of `points` grid points: times plus 3 levels x 3 coordinates per body."""
    return 8.0 * points * (1 + 9 * bodies)


def check_grid(name: str, points: float, bodies: int) -> None:
    """Refuse a grid whose trajectory would exceed MAX_TRAJECTORY_BYTES, before allocating it."""
    if not math.isfinite(points) or points < 2:
        raise ScenarioError(f"{name}: the grid needs at least 2 points, got {points:g}")
    size = trajectory_bytes(points, bodies)
    if size > MAX_TRAJECTORY_BYTES:
        most = math.floor(MAX_TRAJECTORY_BYTES / trajectory_bytes(1, bodies)) - 1
        raise ScenarioError(
            f"{name}: {points:.4g} grid points of {bodies} bodies would take {size / 1024**3:.3g} GiB, "
            f"above the limit of {MAX_TRAJECTORY_BYTES / 1024**3:g} GiB of trajectory; use at most {most} steps"
        )
