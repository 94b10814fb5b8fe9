"""The linkage examples on the native solver against their closed forms
(tests/support/examples/closed_forms.py)."""

from __future__ import annotations

import numpy as np

from reference_solver import solve
from tests.support.examples.closed_forms import (
    crank_rocker_from_rocker,
    peaucellier_lipkin,
    watt_linkage,
    watt_six_bar,
    watt_straight_line,
)
from tests.support.examples.files import example, max_errors

# Closed form and solver agree to rounding (measured: 1e-15 m, 1e-14 m/s, 1e-13 m/s^2 at most).
TOLERANCE = {"position": 1e-13, "velocity": 1e-12, "acceleration": 1e-11}


def _assert_close(errors: dict[str, float]) -> None:
    for level, error in errors.items():
        assert error < TOLERANCE[level], (level, error)


def test_watt_six_bar() -> None:
    scenario = example("watt_six_bar")
    _assert_close(max_errors(scenario, watt_six_bar(np.asarray(scenario.times()))))


def test_watt_straight_line_against_closed_form() -> None:
    scenario = example("watt_straight_line")
    _assert_close(max_errors(scenario, watt_straight_line(np.asarray(scenario.times()))))


def test_watt_midpoint_is_nearly_straight() -> None:
    """M strays from x = 0.2 by under 0.3 % of its travel, and only at fifth order in the swing.

    With equal rockers the linkage is symmetric about M's mid position, so M's stray is odd in the
    swing angle theta; its theta^3 term is -L a2 / 2 with phi = -theta + a2 theta^2 + ... the right
    rocker's angle, and the coupler's length condition at order theta^2 gives -2 c L a2 = 0. So
    halving the swing divides the stray by about 2^5 = 32.
    """
    scenario = example("watt_straight_line")
    position = solve(scenario).position
    assert position is not None
    x, y = position[:, 1, 0], position[:, 1, 1]
    stray, travel = float(np.max(np.abs(x - 0.2))), float(np.ptp(y))
    assert travel > 0.11
    assert stray < 3e-3 * travel
    t = np.linspace(0.0, 1.0, 401)
    wide, narrow = watt_linkage(t), watt_linkage(t, swing=0.15)
    stray_wide = np.max(np.abs((wide[1].p[:, 0] + wide[2].p[:, 0]) / 2 - 0.2))
    stray_narrow = np.max(np.abs((narrow[1].p[:, 0] + narrow[2].p[:, 0]) / 2 - 0.2))
    assert 26.0 < stray_wide / stray_narrow < 40.0


def test_peaucellier_against_closed_form() -> None:
    scenario = example("peaucellier_lipkin")
    _assert_close(max_errors(scenario, peaucellier_lipkin(np.asarray(scenario.times()))))


def test_peaucellier_point_moves_exactly_straight() -> None:
    """P is the inverse of A in the circle of radius sqrt(l^2 - s^2) about O; A's circle passes
    through O, so P stays on x = (l^2 - s^2) / (2 r), with no x velocity or acceleration."""
    trajectory = solve(example("peaucellier_lipkin"))
    assert trajectory.position is not None and trajectory.velocity is not None
    assert trajectory.acceleration is not None
    k = trajectory.bodies.index("bp")
    line = (0.3**2 - 0.15**2) / (2 * 0.12)
    assert np.max(np.abs(trajectory.position[:, k, 0] - line)) < 1e-13
    assert np.max(np.abs(trajectory.velocity[:, k, 0])) < 1e-12
    assert np.max(np.abs(trajectory.acceleration[:, k, 0])) < 1e-11
    assert np.ptp(trajectory.position[:, k, 1]) > 0.3  # it really travels: |y| up to 0.154 m


def test_crank_rocker_driven_from_the_rocker() -> None:
    scenario = example("crank_rocker_from_rocker")
    expected = crank_rocker_from_rocker(np.asarray(scenario.times()))
    # The window keeps crank and coupler well out of line (the dead points).
    crank, coupler = expected["crank"][0][:, 2], expected["coupler"][0][:, 2]
    assert np.min(np.abs(np.sin(coupler - crank))) > 0.2
    _assert_close(max_errors(scenario, expected))
