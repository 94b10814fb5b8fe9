"""Outputs at the grid's times from a march on the step's own lattice, so that the output grid never
changes how an engine integrates.

An engine marches whole steps t0 + k h from the grid's first time. An output time on the lattice is
read as reached. One between two lattice points is reached by a side step: from a copy of the
lattice state before it, one step of the remainder, after which the march goes on from the lattice
state (the copy is dropped). Where an engine cannot take a side step (Exudyn's solver runs in one
call), the output is the quintic Hermite interpolant of the two lattice states around it in
position, velocity and acceleration: an error of order h^6, h^5 and h^4 at the three levels, below
the integrator's own.
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
    """Position, velocity and acceleration at fraction s of a step h from the quintic Hermite
    interpolant of (q, v, a) at both ends."""
    q0, v0, a0 = left
    q1, v1, a1 = right
    # the quintic in s with q, h v, h^2 a at s = 0 and 1
    d0, d1, e0, e1 = h * v0, h * v1, h * h * a0, h * h * a1
    c3 = 10.0 * (q1 - q0) - 6.0 * d0 - 4.0 * d1 - 1.5 * e0 + 0.5 * e1
    c4 = -15.0 * (q1 - q0) + 8.0 * d0 + 7.0 * d1 + 1.5 * e0 - e1
    c5 = 6.0 * (q1 - q0) - 3.0 * d0 - 3.0 * d1 - 0.5 * e0 + 0.5 * e1
    q = q0 + s * (d0 + s * (0.5 * e0 + s * (c3 + s * (c4 + s * c5))))
    dq = d0 + s * (e0 + s * (3.0 * c3 + s * (4.0 * c4 + s * 5.0 * c5)))
    ddq = e0 + s * (6.0 * c3 + s * (12.0 * c4 + s * 20.0 * c5))
    return q, dq / h, ddq / (h * h)
