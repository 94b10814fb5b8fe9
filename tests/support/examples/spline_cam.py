"""Closed form of examples/cam_roller_spline.toml: a roller follower translating along the y axis on
a spline cam turning about the origin, derived on the pitch curve (no cam-contact equations).

In the cam frame the profile is p(phi) = d(phi) u(phi), u = (cos phi, sin phi), d the periodic cubic
spline through the table; the roller's centre runs on the pitch curve c = p + r n, n the outward
unit normal. The follower's centre, (0, y) in the world, is y e(psi) in the cam frame with
e = (cos psi, sin psi) and psi = pi/2 - theta. So c(phi) = y e(psi): phi by Newton on
cross(e, c(phi)) = 0, then y = e . c. Differentiating once and twice in time, with e' = psi' f
(f = (-sin psi, cos psi)) and f' = -psi' e, gives two 2x2 systems in (phi', y') and (phi'', y''):
    c_phi phi' - e y' = y psi' f
    c_phi phi'' - e y'' = (2 y' psi' + y psi'') f - y psi'^2 e - c_phiphi phi'^2.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.interpolate import CubicSpline

TABLE = (
    *(0.06000, 0.05946, 0.05793, 0.05566, 0.05300, 0.05034, 0.04800, 0.04620),
    *(0.04500, 0.04434, 0.04407, 0.04400, 0.04400, 0.04400, 0.04407, 0.04434),
    *(0.04500, 0.04620, 0.04800, 0.05034, 0.05300, 0.05566, 0.05793, 0.05946),
)
ROLLER, OMEGA = 0.02, 10.0


def _rot(v: np.ndarray) -> np.ndarray:
    """v turned by -90 degrees (the outward normal of a counter-clockwise tangent)."""
    return np.array([v[1], -v[0]])


def pitch(spline: CubicSpline, phi: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The pitch curve c and its first two derivatives in phi."""
    d = [float(spline(phi, k)) for k in range(4)]
    u, w = np.array([math.cos(phi), math.sin(phi)]), np.array([-math.sin(phi), math.cos(phi)])
    p1 = d[1] * u + d[0] * w
    p2 = (d[2] - d[0]) * u + 2.0 * d[1] * w
    p3 = (d[3] - 3.0 * d[1]) * u + (3.0 * d[2] - d[0]) * w
    s = float(np.linalg.norm(p1))
    t = p1 / s
    s1 = float(t @ p2)
    t1 = (p2 - t * s1) / s
    t2 = (p3 - t1 * s1 - t * (t1 @ p2 + t @ p3)) / s - t1 * s1 / s
    return d[0] * u + ROLLER * _rot(t), p1 + ROLLER * _rot(t1), p2 + ROLLER * _rot(t2)


def follower(times: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The follower's height y and its first two time derivatives."""
    n = len(TABLE)
    spline = CubicSpline(np.linspace(0.0, 2.0 * math.pi, n + 1), [*TABLE, TABLE[0]], bc_type="periodic")
    out = np.empty((3, len(times)))
    phi = math.pi / 2
    dpsi = -OMEGA
    for i, t in enumerate(times):
        psi = math.pi / 2 - OMEGA * t
        e, f = np.array([math.cos(psi), math.sin(psi)]), np.array([-math.sin(psi), math.cos(psi)])
        for _ in range(50):
            c, c1, _ = pitch(spline, phi)
            step = (e[0] * c[1] - e[1] * c[0]) / (e[0] * c1[1] - e[1] * c1[0])
            phi -= step
            if abs(step) < 1e-15:
                break
        c, c1, c2 = pitch(spline, phi)
        y = float(e @ c)
        matrix = np.column_stack([c1, -e])
        dphi, dy = np.linalg.solve(matrix, y * dpsi * f)
        _, ddy = np.linalg.solve(matrix, 2.0 * dy * dpsi * f - y * dpsi**2 * e - c2 * dphi**2)
        out[:, i] = y, dy, ddy
    return out[0], out[1], out[2]


def cam_roller_spline(times: np.ndarray) -> dict[str, tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """The cam turning at OMEGA from 0; the follower at (0, y) without turning."""
    zero, one = np.zeros_like(times), np.ones_like(times)
    y, dy, ddy = follower(times)
    cam = (
        np.column_stack([zero, zero, OMEGA * times]),
        np.column_stack([zero, zero, OMEGA * one]),
        np.column_stack([zero, zero, zero]),
    )
    return {
        "cam": cam,
        "follower": tuple(np.column_stack([zero, v, zero]) for v in (y, dy, ddy)),  # type: ignore[dict-item]
    }
