"""The bounds of what a scenario makes, checked once it is built and before its grid is
allocated (each parameter is checked against its own declared range in scenarios.family before):

- the end time (from the parameters: turns over a speed, periods) is in [MIN_T_END, MAX_T_END] seconds;
- a trajectory (grid points x bodies x 3 coordinates x 3 levels, 8 bytes each) is at most
  MAX_TRAJECTORY_BYTES (512 MiB, so that a run holding it about four times stays within 2 GiB:
  `--steps 9000000` on a slider-crank went past 4 GB), estimated from the grid's size before it is
  allocated, so that
  `--steps 1e9` or `--dt 1e-15` is one refusal naming the limit, never a kernel OOM kill.
"""

from __future__ import annotations

import math

from scenarios.names import MAX_NAME_LENGTH
from scenarios.scenario import ScenarioError

MAX_T_END = 1e6  # seconds
MIN_T_END = 1e-9  # seconds: below it a grid's times are not apart in floating point (5e-324 gave equal times)
MAX_RUN_BYTES = 2 * 1024**3
"""What one run may hold: its trajectory is held about COPIES_PER_RUN times over (the truth, the
engine's own record, the canonical trajectory, the differences), so a trajectory may take a quarter."""
COPIES_PER_RUN = 4
MAX_TRAJECTORY_BYTES = MAX_RUN_BYTES // COPIES_PER_RUN
MAX_KEPT_BYTES = 4 * 1024**3
"""What a whole `run` keeps for its report: per scenario the truth's and each engine's default
trajectory (trajectories.parquet), estimated from the grids before anything runs."""
MAX_LABEL_LENGTH = MAX_NAME_LENGTH
"""The most characters of a label (`compare --label`, the API's `label`): a name's
(scenarios.names, which also bounds it in bytes where it becomes a file name)."""


def check_t_end(name: str, t_end: float) -> None:
    if not (math.isfinite(t_end) and MIN_T_END <= t_end <= MAX_T_END):
        raise ScenarioError(
            f"{name}: the end time must be in [{MIN_T_END:g}, {MAX_T_END:g}] s, got {t_end:g}"
        )


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
            f"above the limit of {MAX_TRAJECTORY_BYTES / 1024**3:g} GiB of trajectory; "
            f"use at most {most} steps"
        )


def check_kept(trajectories: list[tuple[float, int]]) -> None:
    """Refuse a run whose kept trajectories (grid points, bodies) would exceed MAX_KEPT_BYTES."""
    size = sum(trajectory_bytes(points, bodies) for points, bodies in trajectories)
    if size > MAX_KEPT_BYTES:
        raise ScenarioError(
            f"the run would keep {size / 1024**3:.3g} GiB of trajectories for its report (the truth's "
            f"and each engine's per scenario), more than {MAX_KEPT_BYTES / 1024**3:g} GiB: "
            "fewer --steps, scenarios or engines"
        )
