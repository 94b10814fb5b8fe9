"""Outputs at the grid's times from a march on the step's own lattice, so that the output grid does
not change how an engine integrates.

An engine marches whole steps t0 + k h from the grid's first time. An output time on the lattice is
read as reached. One between two lattice points is reached by a side step: from a copy of the
lattice state before it, one step of the remainder, after which the march goes on from the lattice
state (the copy is dropped). An engine that cannot take a side step (Exudyn's solver runs in one
call) shortens its step so that an even grid's outputs fall on its steps (`outputs_on_steps`); an
uneven grid's output between two steps is interpolated from the two lattice states around it, each
level from itself and its derivative (cubic Hermite for positions and velocities, linear for
accelerations: an error of order h^4, h^4 and h^2 of the motion's own derivatives), with an estimate
of what that costs (`interpolation_cost`).
"""

from __future__ import annotations

import math

import numpy as np

ON_LATTICE = 1e-9
"""A remainder below this fraction of the step counts as on the lattice (round-off of t0 + k h)."""


def lattice_point(t0: float, t: float, h: float) -> tuple[int, float]:
    """(k, r): the last lattice point t0 + k h at or before t, and the remainder r = t - t0 - k h
    (0 on the lattice)."""
    ratio = (t - t0) / h
    k = math.floor(ratio + ON_LATTICE)
    rest = (t - t0) - k * h
    return k, (0.0 if abs(rest) <= ON_LATTICE * h else rest)


def check_grid(times: np.ndarray, start: float) -> None:
    """ValueError unless the output times rise from `start` (a march only goes forward)."""
    grid = np.asarray(times, dtype=float)
    if grid.size and (grid[0] < start or np.any(np.diff(grid) < 0.0)):
        raise ValueError(f"the output times must rise from t = {start:g}")


def lattice_steps(t0: float, t_last: float, h: float) -> int:
    """Whole steps from t0 that reach or pass t_last."""
    k, rest = lattice_point(t0, t_last, h)
    return k + (1 if rest > 0.0 else 0)


def hermite(
    s: float, h: float, left: tuple[np.ndarray, np.ndarray, np.ndarray], right: tuple[np.ndarray, ...]
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Position, velocity and acceleration at fraction s of a step h between two states (q, v, a):
    each level from itself and its derivative (cubic Hermite in q and v; v and a), the acceleration
    linear. No level is differentiated from another: an integrator's velocity error of order h^2
    would otherwise reach the accelerations divided by h."""
    q0, v0, a0 = left
    q1, v1, a1 = right
    return _cubic(s, h, q0, v0, q1, v1), _cubic(s, h, v0, a0, v1, a1), (1.0 - s) * a0 + s * a1


def _cubic(s: float, h: float, y0: np.ndarray, d0: np.ndarray, y1: np.ndarray, d1: np.ndarray) -> np.ndarray:
    """The cubic Hermite interpolant of values y and slopes d at fraction s of a step h."""
    h00, h10 = (1.0 + 2.0 * s) * (1.0 - s) ** 2, s * (1.0 - s) ** 2
    h01, h11 = s * s * (3.0 - 2.0 * s), s * s * (s - 1.0)
    return h00 * y0 + h10 * h * d0 + h01 * y1 + h11 * h * d1  # type: ignore[no-any-return]


def outputs_on_steps(times: np.ndarray, h: float) -> float:
    """The step the march takes so that every output time falls on it: `h` where the grid's times
    are already whole steps from its first (or it has one time), else, for an evenly spaced grid, the
    output spacing over the fewest whole steps no longer than `h` (spacing / ceil(spacing / h)); `h`
    for an uneven grid, whose outputs between steps are then interpolated (`hermite`)."""
    grid = np.asarray(times, dtype=float)
    if grid.size < 2:
        return h
    t0 = float(grid[0])
    if all(lattice_point(t0, float(t), h)[1] == 0.0 for t in grid):
        return h
    gaps = np.diff(grid)
    spacing = float(grid[-1] - t0) / (grid.size - 1)
    if spacing <= 0.0 or np.max(np.abs(gaps - spacing)) > ON_LATTICE * spacing:
        return h
    return spacing / math.ceil(spacing / h * (1.0 - ON_LATTICE))


def interpolation_cost(
    s: float, h: float, left: tuple[np.ndarray, np.ndarray, np.ndarray], right: tuple[np.ndarray, ...]
) -> np.ndarray:
    """An estimate of the position error `hermite` makes at fraction s of a step h, per coordinate:
    its difference from the quintic Hermite interpolant, which also matches both states'
    accelerations (one order closer to the motion)."""
    q0, v0, a0 = left
    q1, v1, a1 = right
    s2, s3, s4, s5 = s * s, s**3, s**4, s**5
    quintic = (
        (1.0 - 10.0 * s3 + 15.0 * s4 - 6.0 * s5) * q0
        + (s - 6.0 * s3 + 8.0 * s4 - 3.0 * s5) * h * v0
        + (0.5 * s2 - 1.5 * s3 + 1.5 * s4 - 0.5 * s5) * h * h * a0
        + (0.5 * s3 - s4 + 0.5 * s5) * h * h * a1
        + (-4.0 * s3 + 7.0 * s4 - 3.0 * s5) * h * v1
        + (10.0 * s3 - 15.0 * s4 + 6.0 * s5) * q1
    )
    return np.abs(quintic - _cubic(s, h, q0, v0, q1, v1))  # type: ignore[no-any-return]
