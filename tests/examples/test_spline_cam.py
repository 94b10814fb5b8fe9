"""examples/cam_roller_spline.toml: the native solver against the pitch-curve closed form, and
MuJoCo's faceted model of the spline converging with its piece count.

Measured (2026-11, MuJoCo 4.0 at its default: RK4, dt = 1/2000 of the turn, tc 4 steps, contact
solimp 0.99, preload 100 N), the follower's largest error against the closed form (m, m/s, m/s^2):

    pieces   position  velocity  acceleration
      256    5.3e-5    9.2e-2    5.1e2   (thrown off the vertices: the preload over the mass)
      512    3.9e-6    2.4e-3    1.4e1   (the default)
     1024    2.1e-6    1.3e-3    7.6
     2048    1.3e-6    7.4e-4    4.1
     4096    9.0e-7    6.3e-4    3.3

From 512 pieces on the errors fall at order 0.6 to 0.9 in the piece count, as on the family's
spline cam (tests/adapters/mujoco/test_cam_facets.py): the soft contact's kinks at the vertices,
not the sagitta, set them.
"""

from __future__ import annotations

import numpy as np
import pytest

from adapters.mujoco import MujocoAdapter
from tests.support.examples.files import example, max_errors
from tests.support.examples.spline_cam import cam_roller_spline

# Closed form and solver agree to rounding (measured 2.8e-17 m, 3.7e-15 m/s, 7.3e-15 m/s^2).
TOLERANCE = {"position": 1e-13, "velocity": 1e-12, "acceleration": 1e-11}


def test_native_solver_against_the_pitch_curve() -> None:
    scenario = example("cam_roller_spline")
    expected = cam_roller_spline(np.asarray(scenario.times()))
    rise = np.ptp(expected["follower"][0][:, 1])
    assert 0.015 < rise < 0.017  # the profile's 0.06 - 0.044 m, through the roller
    for level, error in max_errors(scenario, expected).items():
        assert error < TOLERANCE[level], (level, error)


def _mujoco_errors(pieces: int) -> np.ndarray:
    """The follower's largest error per level in MuJoCo at its default with `pieces` facets."""
    scenario = example("cam_roller_spline")
    adapter = MujocoAdapter()
    times = np.asarray(scenario.times())
    result = adapter.run(scenario, adapter.default_setting(scenario).replace(cam_pieces=pieces), times)
    assert result.status == "ok" and result.trajectory is not None, result.message
    k = result.trajectory.bodies.index("follower")
    expected = cam_roller_spline(times)["follower"]
    found = []
    for got, want in zip(
        (result.trajectory.position, result.trajectory.velocity, result.trajectory.acceleration),
        expected,
        strict=True,
    ):
        assert got is not None
        found.append(float(np.abs(got[:, k, :] - want).max()))
    return np.array(found)


@pytest.mark.slow
def test_mujoco_facets_converge_with_the_piece_count() -> None:
    """Four times the pieces: every level at least twice closer (measured 3.0, 3.2, 3.5 times)."""
    coarse, fine = _mujoco_errors(512), _mujoco_errors(2048)
    assert coarse[0] < 1.2e-5 and coarse[1] < 7e-3 and coarse[2] < 45.0  # 3x the measured default
    assert np.all(fine < coarse / 2.0), (coarse, fine)
