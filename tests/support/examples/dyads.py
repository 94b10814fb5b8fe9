"""Closed-form kinematics of linkages built from driven links and RRR dyads, for the examples' tests.

Positions come from intersecting two circles (the dyad's two links about their known ends); rates
from differentiating the two length conditions by hand, |X - P|^2 = l^2, which gives a 2x2 linear
system per level. None of this shares code or formulation with the native solver (absolute
coordinates and Newton-Raphson on the joint equations).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Motion2:
    """A point's position, velocity and acceleration over time, arrays of shape (N, 2)."""

    p: np.ndarray
    v: np.ndarray
    a: np.ndarray


@dataclass(frozen=True)
class Angle:
    """An angle, its rate and its acceleration over time, arrays of shape (N,)."""

    theta: np.ndarray
    omega: np.ndarray
    alpha: np.ndarray


def cross(u: np.ndarray, w: np.ndarray) -> np.ndarray:
    return u[:, 0] * w[:, 1] - u[:, 1] * w[:, 0]


def dot(u: np.ndarray, w: np.ndarray) -> np.ndarray:
    return np.einsum("ij,ij->i", u, w)


def turn(u: np.ndarray) -> np.ndarray:
    """u turned by +90 degrees."""
    return np.column_stack([-u[:, 1], u[:, 0]])


def fixed(point: tuple[float, float], n: int) -> Motion2:
    zero = np.zeros((n, 2))
    return Motion2(np.tile(point, (n, 1)), zero, zero.copy())


def on_body(origin: Motion2, angle: Angle, local: tuple[float, float]) -> Motion2:
    """The point at `local` in a frame at `origin` turned by `angle`."""
    c, s = np.cos(angle.theta), np.sin(angle.theta)
    r = np.column_stack([c * local[0] - s * local[1], s * local[0] + c * local[1]])
    w, al = angle.omega[:, None], angle.alpha[:, None]
    return Motion2(origin.p + r, origin.v + w * turn(r), origin.a + al * turn(r) - w**2 * r)


def direction(start: Motion2, end: Motion2) -> Angle:
    """The angle of the vector from `start` to `end` (continuous), with its two rates."""
    u, du, ddu = end.p - start.p, end.v - start.v, end.a - start.a
    n2 = dot(u, u)
    omega = cross(u, du) / n2
    alpha = cross(u, ddu) / n2 - 2.0 * dot(u, du) * omega / n2
    return Angle(np.unwrap(np.arctan2(u[:, 1], u[:, 0])), omega, alpha)


def dyad(p1: Motion2, p2: Motion2, l1: float, l2: float, side: float) -> Motion2:
    """The joint X with |X - p1| = l1 and |X - p2| = l2, on the left of p1 -> p2 for side = +1."""
    d = p2.p - p1.p
    dist = np.sqrt(dot(d, d))
    along = (l1**2 - l2**2 + dist**2) / (2.0 * dist)
    height = np.sqrt(l1**2 - along**2)
    x = p1.p + (along / dist)[:, None] * d + side * (height / dist)[:, None] * turn(d)
    u1, u2 = x - p1.p, x - p2.p
    det = cross(u1, u2)

    def solve(r1: np.ndarray, r2: np.ndarray) -> np.ndarray:
        # rows u1 . X' = r1 and u2 . X' = r2, by Cramer's rule
        return np.column_stack([(r1 * u2[:, 1] - u1[:, 1] * r2) / det, (u1[:, 0] * r2 - r1 * u2[:, 0]) / det])

    v = solve(dot(u1, p1.v), dot(u2, p2.v))
    w1, w2 = v - p1.v, v - p2.v
    a = solve(dot(u1, p1.a) - dot(w1, w1), dot(u2, p2.a) - dot(w2, w2))
    return Motion2(x, v, a)


def frame(origin: Motion2, angle: Angle, offset: float = 0.0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A body's (x, y, theta) per level, its frame at `origin`, its x axis at `angle` + `offset`."""
    return (
        np.column_stack([origin.p, angle.theta + offset]),
        np.column_stack([origin.v, angle.omega]),
        np.column_stack([origin.a, angle.alpha]),
    )


def driven(theta: np.ndarray, omega: np.ndarray, alpha: np.ndarray) -> Angle:
    return Angle(theta, omega, alpha)
