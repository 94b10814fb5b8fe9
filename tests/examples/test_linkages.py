"""The linkage examples on the native solver against their closed forms (tests/examples/dyads.py)."""

from __future__ import annotations

import numpy as np

from reference_solver import solve
from tests.examples.dyads import Angle, Motion2, direction, dyad, fixed, frame, on_body
from tests.examples.support import example, max_errors

# Closed form and solver agree to rounding (measured: 1e-15 m, 1e-14 m/s, 1e-13 m/s^2 at most).
TOLERANCE = {"position": 1e-13, "velocity": 1e-12, "acceleration": 1e-11}


def _assert_close(errors: dict[str, float]) -> None:
    for level, error in errors.items():
        assert error < TOLERANCE[level], (level, error)


def _constant_speed(times: np.ndarray, start: float, rate: float) -> Angle:
    return Angle(start + rate * times, np.full_like(times, rate), np.zeros_like(times))


def _harmonic(times: np.ndarray, mean: float, amplitude: float, omega: float) -> Angle:
    c, s = np.cos(omega * times), np.sin(omega * times)
    return Angle(mean + amplitude * c, -amplitude * omega * s, -amplitude * omega**2 * c)


def test_watt_six_bar() -> None:
    scenario = example("watt_six_bar")
    t = np.asarray(scenario.times())
    o2, o4, o6 = fixed((0.0, 0.0), t.size), fixed((0.3, 0.0), t.size), fixed((0.45, -0.3), t.size)
    crank = _constant_speed(t, 0.0, 10.0)
    a = on_body(o2, crank, (0.1, 0.0))
    b = dyad(a, o4, 0.3, 0.25, 1.0)
    ternary = direction(o4, b)
    c = on_body(o4, ternary, (-0.15, 0.0))
    d = dyad(c, o6, 0.25, 0.2, 1.0)
    expected = {
        "crank": frame(o2, crank),
        "coupler": frame(a, direction(a, b)),
        "ternary": frame(o4, ternary),
        "link5": frame(c, direction(c, d)),
        "output": frame(o6, direction(o6, d)),
    }
    _assert_close(max_errors(scenario, expected))


def _watt(t: np.ndarray) -> tuple[Angle, Motion2, Motion2, Motion2]:
    o2, o4 = fixed((0.0, 0.0), t.size), fixed((0.4, 0.1), t.size)
    left = _harmonic(t, 0.0, 0.3, 2.0 * np.pi)
    a = on_body(o2, left, (0.2, 0.0))
    b = dyad(a, o4, 0.1, 0.2, 1.0)
    return left, a, b, o4


def test_watt_straight_line_against_closed_form() -> None:
    scenario = example("watt_straight_line")
    t = np.asarray(scenario.times())
    left, a, b, o4 = _watt(t)
    coupler = direction(a, b)
    midpoint = on_body(a, coupler, (0.05, 0.0))
    expected = {
        "rocker_left": frame(fixed((0.0, 0.0), t.size), left),
        "coupler": frame(midpoint, coupler),
        "rocker_right": frame(o4, direction(o4, b)),
    }
    _assert_close(max_errors(scenario, expected))


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
    wide = _watt(t)
    narrow_angle = _harmonic(t, 0.0, 0.15, 2.0 * np.pi)
    narrow_a = on_body(fixed((0.0, 0.0), t.size), narrow_angle, (0.2, 0.0))
    narrow_b = dyad(narrow_a, fixed((0.4, 0.1), t.size), 0.1, 0.2, 1.0)
    stray_wide = np.max(np.abs((wide[1].p[:, 0] + wide[2].p[:, 0]) / 2 - 0.2))
    stray_narrow = np.max(np.abs((narrow_a.p[:, 0] + narrow_b.p[:, 0]) / 2 - 0.2))
    assert 26.0 < stray_wide / stray_narrow < 40.0


def test_peaucellier_against_closed_form() -> None:
    scenario = example("peaucellier_lipkin")
    t = np.asarray(scenario.times())
    origin, pivot = fixed((0.0, 0.0), t.size), fixed((0.12, 0.0), t.size)
    crank = _constant_speed(t, -1.0, 1.0)
    a = on_body(pivot, crank, (0.12, 0.0))
    b, d = dyad(origin, a, 0.3, 0.15, 1.0), dyad(origin, a, 0.3, 0.15, -1.0)
    p = dyad(b, d, 0.15, 0.15, 1.0)
    expected = {
        "crank": frame(pivot, crank),
        "ob": frame(origin, direction(origin, b)),
        "od": frame(origin, direction(origin, d)),
        "ab": frame(a, direction(a, b)),
        "ad": frame(a, direction(a, d)),
        "bp": frame(p, direction(p, b)),
        "dp": frame(p, direction(p, d)),
    }
    _assert_close(max_errors(scenario, expected))


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
    t = np.asarray(scenario.times())
    o2, o4 = fixed((0.0, 0.0), t.size), fixed((0.3, 0.0), t.size)
    rocker = _harmonic(t, 1.97, 0.35, 2.0)
    b = on_body(o4, rocker, (0.25, 0.0))
    a = dyad(o2, b, 0.1, 0.3, -1.0)
    crank, coupler = direction(o2, a), direction(a, b)
    # The window keeps crank and coupler well out of line (the dead points).
    assert np.min(np.abs(np.sin(coupler.theta - crank.theta))) > 0.2
    expected = {
        "crank": frame(o2, crank),
        "coupler": frame(a, coupler),
        "rocker": frame(o4, rocker),
    }
    _assert_close(max_errors(scenario, expected))
