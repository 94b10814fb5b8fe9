"""A cam profile sampled at many angles at once, bit for bit the per-angle functions.

The facets, the tip sphere's radius and checks, and the polygon's sagitta (adapters.mujoco.cam_facets,
cam_tip) sample the profile at hundreds to thousands of angles for every build; one Python call per
angle (SplineProfile.radii, profile_point and the offset point built on it) cost about a second of
a spline cam's build.
Here each sample is the same floating-point operations in the same order, on arrays: a spline's
cubic pieces are evaluated as SplineProfile.radii does (numpy evaluates each operation apart, with
no fused multiply-add), the angles' cosines and sines come from math as in profile_point, and the
2-vector norms and dot products go through the same BLAS dot as np.linalg.norm and `@` on one
vector (a stacked matmul of 1 x 2 by 2 x 1 calls it per row), which may fuse a multiply-add and so
differ in the last bit from a sum of squares. tests/adapters/mujoco/test_cam_samples.py compares
every function here with the per-angle construction for equality.
"""

from __future__ import annotations

import math

import numpy as np

from scenarios.cam_profiles import Profile, SplineProfile

TWO_PI = 2.0 * math.pi


def radii_at(profile: Profile, phis: np.ndarray) -> np.ndarray:
    """(len(phis), 4): d(phi) and its first three derivatives at each angle, as profile.radii."""
    if not isinstance(profile, SplineProfile):  # closed forms: few samples, kept per angle
        return np.array([profile.radii(float(p)) for p in phis], dtype=float).reshape(len(phis), 4)
    pieces = np.array(profile.pieces, dtype=float)
    width = TWO_PI / len(pieces)
    p = np.fmod(np.asarray(phis, dtype=float), TWO_PI)
    p = np.where(p < 0.0, p + TWO_PI, p)
    k = np.minimum((p / width).astype(np.int64), len(pieces) - 1)
    x = p - k * width
    c0, c1, c2, c3 = pieces[k].T
    return np.stack(
        [
            c0 + x * (c1 + x * (c2 + x * c3)),
            c1 + x * (2.0 * c2 + 3.0 * c3 * x),
            2.0 * c2 + 6.0 * c3 * x,
            6.0 * c3,
        ],
        axis=1,
    )


def row_dots(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Each row's a_i @ b_i, by the dot of `a_i @ b_i` on two vectors."""
    return (a[:, None, :] @ b[:, :, None]).reshape(len(a))


def row_norms(a: np.ndarray) -> np.ndarray:
    """Each row's np.linalg.norm(a_i) (the square root of its dot with itself)."""
    return np.sqrt(row_dots(a, a))


def points_at(profile: Profile, phis: np.ndarray, inset: float = 0.0) -> np.ndarray:
    """(len(phis), 2): the profile's point at each angle, moved inward along its normal by `inset`
    (left of travel): a point of its inward offset curve."""
    radii = radii_at(profile, phis)
    d0, d1 = radii[:, 0], radii[:, 1]
    cos = np.array([math.cos(float(p)) for p in phis])
    sin = np.array([math.sin(float(p)) for p in phis])
    points = np.stack([d0 * cos, d0 * sin], axis=1)
    if inset == 0.0:
        return points
    velocity = np.stack([d1 * cos + d0 * -sin, d1 * sin + d0 * cos], axis=1)
    tangent = velocity / row_norms(velocity)[:, None]
    return points + inset * np.stack([-tangent[:, 1], tangent[:, 0]], axis=1)


def nearest_distance(a: np.ndarray, b: np.ndarray, block: int = 64) -> float:
    """The least distance between a point of `a` and a point of `b` (rows), as the least of
    np.linalg.norm(b - a_i, axis=1) over a's points: that norm is the square root of dx^2 + dy^2
    added as here, and the square root keeps the order, so the least one is the same number. `block`
    rows of a at a time, in place, so that the temporaries stay small."""
    bx, by = np.ascontiguousarray(b[:, 0]), np.ascontiguousarray(b[:, 1])
    least = math.inf
    for start in range(0, len(a), block):
        dx = bx[None, :] - a[start : start + block, 0, None]
        dy = by[None, :] - a[start : start + block, 1, None]
        dx *= dx
        dy *= dy
        dx += dy
        least = min(least, float(dx.min()))
    return math.sqrt(least)
