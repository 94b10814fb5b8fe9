"""The bounds of what a scenario makes, checked once it is built and before its grid is
allocated (each parameter is checked against its own declared range in scenarios.family before):

- the end time (from the parameters: turns over a speed, periods) is in [MIN_T_END, MAX_T_END] seconds;
- a trajectory (grid points x bodies x 3 coordinates x 3 levels, 8 bytes each) is at most
  MAX_TRAJECTORY_BYTES (512 MiB, so that a run holding it about four times stays within 2 GiB:
  `--steps 9000000` on a slider-crank went past 4 GB), estimated from the grid's size before it is
  allocated, so that
  `--steps 1e9` or `--dt 1e-15` is one refusal naming the limit, never a kernel OOM kill;
- the work (`work_seconds`: constraint rows x grid points, and for dense work rows cubed x grid
  points, at measured costs) is at most MAX_WORK_SECONDS, and a dense solve has at most
  MAX_DENSE_ROWS rows, so that the largest admitted problem ends in about a minute and each call
  that cannot be interrupted (a dense factorization) in about a second: a SIGTERM is honoured
  between two such calls.
"""

from __future__ import annotations

import math

from scenarios.names import MAX_NAME_LENGTH
from scenarios.scenario import Scenario, ScenarioError

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


MAX_WORK_SECONDS = 60.0
"""The estimated CPU time of the largest problem admitted (`work_seconds`)."""
ROW_STEP_SECONDS = 7e-6
"""CPU time per constraint row and grid point of a solve by the native kinematic loop, its CSV
written (4 to 7 microseconds from a 3-body slider-crank at 2e5 steps to a 2001-body chain)."""
DENSE_STEP_SECONDS = 4e-9
"""CPU time per cubed constraint row and grid point of the dense solves: a run's inverse dynamics
(a least-squares solve of C_q^T per grid point, 1.6 to 5.3 ns x n^3 from 60 to 1200 rows on two
cores), an engine's own kinematics and the free dynamics."""
MAX_DENSE_ROWS = 600
"""The most constraint rows of a problem solved densely: one such solve (under a second at 600
rows) runs in compiled code that no signal interrupts."""


def dense(scenario: Scenario) -> bool:
    """Whether the native solver's work on `scenario` is dense: free dynamics is."""
    return scenario.analysis != "kinematic"


def work_seconds(points: float, bodies: int, dense: bool) -> float:
    """Estimated CPU time of `points` grid points of `bodies` bodies (3 constraint rows each):
    linear in the rows for the banded kinematic loop, cubic for `dense` work."""
    rows = 3.0 * bodies
    return points * rows * (ROW_STEP_SECONDS + (DENSE_STEP_SECONDS * rows * rows if dense else 0.0))


def check_work(name: str, points: float, bodies: int, dense: bool) -> None:
    """Refuse, before any work, a problem estimated above MAX_WORK_SECONDS or a dense one of more
    than MAX_DENSE_ROWS rows, naming the limit and what would be admitted."""
    if dense:
        check_dense_rows(name, bodies)
    estimate = work_seconds(points, bodies, dense)
    if estimate > MAX_WORK_SECONDS:
        most = math.floor(MAX_WORK_SECONDS / work_seconds(1, bodies, dense)) - 1
        raise ScenarioError(
            f"{name}: {points:.4g} grid points of {bodies} bodies would take about {estimate:.3g} s "
            f"of work, above the limit of {MAX_WORK_SECONDS:g} s; use at most {max(most, 1)} steps"
        )


def dense_admitted(bodies: int) -> bool:
    """Whether a problem of `bodies` bodies is within MAX_DENSE_ROWS rows for a dense solve."""
    return 3 * bodies <= MAX_DENSE_ROWS


def check_dense_rows(name: str, bodies: int) -> None:
    """Refuse a problem of more than MAX_DENSE_ROWS rows (3 a body) for a dense solve."""
    rows = 3 * bodies
    if not dense_admitted(bodies):
        raise ScenarioError(
            f"{name}: {bodies} bodies make {rows} constraint rows, above the limit of "
            f"{MAX_DENSE_ROWS} rows ({MAX_DENSE_ROWS // 3} bodies) for dense solves (dynamics, the "
            "engines, a run's forces); solve it kinematically with the reference engine"
        )


def check_t_end(name: str, t_end: float) -> None:
    if not (math.isfinite(t_end) and MIN_T_END <= t_end <= MAX_T_END):
        raise ScenarioError(
            f"{name}: the end time must be in [{MIN_T_END:g}, {MAX_T_END:g}] s, got {t_end:g}"
        )


def trajectory_bytes(points: float, bodies: int) -> float:
    """Memory of a trajectory of `points` grid points: times plus 3 levels x 3 coordinates per body."""
    return 8.0 * points * (1 + 9 * bodies)


def check_grid(name: str, points: float, bodies: int, dense: bool = False) -> None:
    """Refuse a grid whose trajectory would exceed MAX_TRAJECTORY_BYTES, or whose work would
    exceed MAX_WORK_SECONDS (`check_work`), before allocating it."""
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
    check_work(name, points, bodies, dense)


def check_kept(trajectories: list[tuple[float, int]]) -> None:
    """Refuse a run whose kept trajectories (grid points, bodies) would exceed MAX_KEPT_BYTES."""
    size = sum(trajectory_bytes(points, bodies) for points, bodies in trajectories)
    if size > MAX_KEPT_BYTES:
        raise ScenarioError(
            f"the run would keep {size / 1024**3:.3g} GiB of trajectories for its report (the truth's "
            f"and each engine's per scenario), more than {MAX_KEPT_BYTES / 1024**3:g} GiB: "
            "fewer --steps, scenarios or engines"
        )
