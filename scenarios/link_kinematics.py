"""Building blocks of the families' closed forms: a point's kinematics along a link, a frame's three
levels, a constant-speed drive, Cramer's rule for the differentiated loop equations, and the
trajectory assembled from the bodies.

Every array is over the time grid: angles (N,), points (N, 2). A point's or frame's kinematics is the
triple (position, velocity, acceleration) of such arrays.
"""

from __future__ import annotations

import math

import numpy as np

from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory

Levels = tuple[np.ndarray, np.ndarray, np.ndarray]
"""Position, velocity and acceleration, one array each, first axis the time grid."""


def unit(theta: np.ndarray) -> np.ndarray:
    """The unit vectors (cos theta, sin theta), shape (N, 2)."""
    return np.stack([np.cos(theta), np.sin(theta)], axis=-1)


def link_point(base: Levels, theta: np.ndarray, omega: np.ndarray, alpha: np.ndarray, s: float) -> Levels:
    """Position, velocity and acceleration of the point at distance s along a link from `base`."""
    p, v, a = base
    e, n = unit(theta), unit(theta + math.pi / 2)
    return (
        p + s * e,
        v + s * omega[:, None] * n,
        a + s * (alpha[:, None] * n - (omega**2)[:, None] * e),
    )


def frame(point: Levels, theta: np.ndarray, omega: np.ndarray, alpha: np.ndarray) -> Levels:
    """Stack a frame's (x, y) kinematics and its angle into (N, 3) arrays per level."""
    p, v, a = point
    return (np.column_stack([p, theta]), np.column_stack([v, omega]), np.column_stack([a, alpha]))


def assemble(
    times: np.ndarray, frames: dict[str, Levels], extras: dict[str, np.ndarray] | None = None
) -> Trajectory:
    """The trajectory of the bodies `frames` names (in its order), each given by `frame`."""
    names = tuple(frames)
    position, velocity, acceleration = (np.stack([frames[b][k] for b in names], axis=1) for k in range(3))
    return Trajectory(np.asarray(times), names, position, velocity, acceleration, extras=extras or {})


def fixed(n: int, x: float, y: float) -> Levels:
    """A point at rest at (x, y) over n grid times."""
    zero = np.zeros((n, 2))
    return (np.tile([x, y], (n, 1)), zero, zero.copy())


def constant_speed(s: Scenario, t: np.ndarray) -> Levels:
    """The driven angle, its rate and acceleration for the scenario's `omega` and `theta0`."""
    omega, theta0 = float(s.parameter("omega")), float(s.parameter("theta0"))
    return theta0 + omega * t, np.full_like(t, omega), np.zeros_like(t)


def solve2(
    m11: np.ndarray,
    m12: np.ndarray,
    m21: np.ndarray,
    m22: np.ndarray,
    r1: np.ndarray,
    r2: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """Cramer's rule for [[m11, m12], [m21, m22]] x = [r1, r2], elementwise."""
    det = m11 * m22 - m12 * m21
    return (r1 * m22 - m12 * r2) / det, (m11 * r2 - r1 * m21) / det
