"""The user-function constraints of the Exudyn adapter (adapters.exudyn.constraints): each
Jacobian block and C_t against central differences of its own residual, and the spline profile's
direct evaluation against the profile's own radii. A wrong entry would not stop Exudyn's Newton
from converging, but it would make the velocity solve on Exudyn's Jacobian wrong."""

from __future__ import annotations

import numpy as np
import pytest

from adapters.exudyn.constraints import UserConstraint, user_constraint
from scenarios import (
    GROUND,
    Constant,
    EccentricDisc,
    FlatFaceCam,
    Harmonic,
    KnifeEdgeCam,
    Point,
    PointPathDriver,
    RackPinion,
    RelativeDisplacementDriver,
    RollerCam,
    SplineProfile,
)

DISC = EccentricDisc(0.05, 0.01)
SPLINE = SplineProfile.sample(DISC, 24)
ITEMS = {
    "knife": KnifeEdgeCam("c", "cam", SPLINE, Point("follower", (0.01, -0.02)), 1.0),
    "roller": RollerCam("c", "cam", DISC, Point("follower", (0.02, 0.01)), 0.02, 1.0),
    "flat": FlatFaceCam("c", "cam", SPLINE, Point("follower", (0.0, 0.01)), (0.3, -1.0), 1.0),
    "rack": RackPinion(
        "m", Point("pinion", (0.01, 0.0)), 0.05, Point("rack", (0.1, -0.03)), (1.0, 0.2), 0.01
    ),
    "path": PointPathDriver("p", Point("block", (0.03, 0.02)), Harmonic(0.1, 0.2, 3.0, 0.5), Constant(0.2)),
    "relative": RelativeDisplacementDriver(
        "d",
        Point("a", (0.01, 0.0)),
        Point("b", (0.0, 0.02)),
        Harmonic(0.0, 0.1, 2.0),
        Harmonic(0.1, 0.05, 4.0),
    ),
    "fixed_cam": KnifeEdgeCam("c", GROUND, DISC, Point("follower", (0.0, 0.0)), 0.5),
}


def _flat(constraint: UserConstraint, poses: list[np.ndarray], extra: np.ndarray, t: float) -> np.ndarray:
    return np.array(constraint.evaluate([p.tolist() for p in poses], extra.tolist(), t)[0])


@pytest.mark.parametrize("kind", ITEMS)
def test_jacobian_blocks_and_time_derivative_match_differences(kind: str) -> None:
    constraint = user_constraint(ITEMS[kind])
    assert constraint is not None
    rng = np.random.default_rng(7)
    for _ in range(5):
        poses = [rng.uniform(-1.0, 1.0, 3) for _ in constraint.bodies]
        extra, t, h = rng.uniform(-3.0, 3.0, constraint.extra), float(rng.uniform(0.0, 1.0)), 1e-6
        _, blocks, extra_block, c_t = constraint.evaluate([p.tolist() for p in poses], extra.tolist(), t)
        for b in range(len(poses)):
            for k in range(3):
                up, down = [p.copy() for p in poses], [p.copy() for p in poses]
                up[b][k] += h
                down[b][k] -= h
                numeric = (_flat(constraint, up, extra, t) - _flat(constraint, down, extra, t)) / (2 * h)
                np.testing.assert_allclose(np.array(blocks[b])[:, k], numeric, atol=1e-8)
        for k in range(constraint.extra):
            step = np.eye(constraint.extra)[k] * h
            numeric = (
                _flat(constraint, poses, extra + step, t) - _flat(constraint, poses, extra - step, t)
            ) / (2 * h)
            np.testing.assert_allclose(np.array(extra_block)[:, k], numeric, atol=1e-8)
        numeric = (_flat(constraint, poses, extra, t + h) - _flat(constraint, poses, extra, t - h)) / (2 * h)
        np.testing.assert_allclose(c_t, numeric, atol=1e-8)
