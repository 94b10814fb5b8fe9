"""The drivers' rows at a hand-worked time: C = (what is driven) - f(t), C_t = -f'(t), and the
right-hand side of the acceleration equation Q_d = -(C_q q_dot)_q q_dot - C_tt, where C_tt = -f''(t).

The motion law is harmonic, f = mean + A cos(omega t + phase), at omega t + phase = pi/3:
f = mean + A/2, f' = -A omega sqrt(3)/2, f'' = -A omega^2 / 2.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from scenarios import (
    AbsoluteDriver,
    Harmonic,
    Point,
    PointPathDriver,
    RelativeDisplacementDriver,
    RelativeRotationDriver,
)
from tests.support.constraint_systems import coordinates, system_of

T = 0.25
OMEGA = 2.0
PHASE = math.pi / 3 - OMEGA * T  # omega T + phase = pi / 3


def law(mean: float, amplitude: float) -> tuple[Harmonic, float, float, float]:
    """The motion and its f, f', f'' at T, worked by hand."""
    root3 = math.sqrt(3.0)
    f, df, ddf = mean + amplitude / 2, -amplitude * OMEGA * root3 / 2, -amplitude * OMEGA**2 / 2
    return Harmonic(mean, amplitude, OMEGA, PHASE), f, df, ddf


POSES = {"a": (1.0, 2.0, math.pi / 2), "b": (0.5, -1.0, 0.25)}


def rows(driver, poses, rates=None):  # type: ignore[no-untyped-def]
    """C, C_t and Q_d of one driver at T (rates default to zero)."""
    system = system_of(driver)
    qd = coordinates(rates or {})
    c, _, q_d = system.evaluate(coordinates(poses), T, qd)
    return c, system.c_t(T), q_d


@pytest.mark.parametrize("coordinate, k", [("x", 0), ("y", 1), ("theta", 2)])
def test_an_absolute_driver_is_its_coordinate_less_the_law(coordinate: str, k: int) -> None:
    motion, f, df, ddf = law(0.3, 1.5)
    c, c_t, q_d = rows(AbsoluteDriver("d", "a", coordinate, motion), POSES)  # type: ignore[arg-type]
    np.testing.assert_allclose(c, [POSES["a"][k] - f], rtol=0, atol=1e-15)
    np.testing.assert_allclose(c_t, [-df], rtol=1e-15)
    np.testing.assert_allclose(q_d, [ddf], rtol=1e-15)


def test_a_relative_rotation_driver_is_the_angle_between_the_bodies_less_the_law() -> None:
    motion, f, df, ddf = law(0.3, 1.5)
    c, c_t, q_d = rows(RelativeRotationDriver("d", "a", "b", motion), POSES)
    np.testing.assert_allclose(c, [math.pi / 2 - 0.25 - f], rtol=0, atol=1e-15)
    np.testing.assert_allclose(c_t, [-df], rtol=1e-15)
    np.testing.assert_allclose(q_d, [ddf], rtol=1e-15)


def test_a_point_path_driver_on_a_turning_body() -> None:
    """a's local (1, 0), turned by 90 degrees, is at (1, 2) + (0, 1); a turning at 2 rad/s adds the
    point's centripetal acceleration -(0, 1) * 2^2 to the path's, so Q_d = (0, 4) + (fx'', fy'')."""
    (mx, fx, dfx, ddfx), (my, fy, dfy, ddfy) = law(0.3, 1.5), law(-0.2, 0.8)
    c, c_t, q_d = rows(PointPathDriver("d", Point("a", (1.0, 0.0)), mx, my), POSES, {"a": (0.0, 0.0, 2.0)})
    np.testing.assert_allclose(c, [1.0 - fx, 3.0 - fy], rtol=0, atol=1e-15)
    np.testing.assert_allclose(c_t, [-dfx, -dfy], rtol=1e-15)
    np.testing.assert_allclose(q_d, [0.0 + ddfx, 4.0 + ddfy], rtol=0, atol=1e-14)


def test_a_relative_displacement_driver_between_two_points() -> None:
    """a's local (1, 0) at (1, 3) as above; b's local (0, 0) at (0.5, -1): r_a - r_b = (0.5, 4)."""
    (mx, fx, dfx, ddfx), (my, fy, dfy, ddfy) = law(0.3, 1.5), law(-0.2, 0.8)
    driver = RelativeDisplacementDriver("d", Point("a", (1.0, 0.0)), Point("b"), mx, my)
    c, c_t, q_d = rows(driver, POSES, {"a": (0.0, 0.0, 2.0)})
    np.testing.assert_allclose(c, [0.5 - fx, 4.0 - fy], rtol=0, atol=1e-15)
    np.testing.assert_allclose(c_t, [-dfx, -dfy], rtol=1e-15)
    np.testing.assert_allclose(q_d, [0.0 + ddfx, 4.0 + ddfy], rtol=0, atol=1e-14)


def test_each_driver_row_is_named_after_its_driver_and_what_it_drives() -> None:
    motion = law(0.0, 1.0)[0]
    system = system_of(
        AbsoluteDriver("ax", "a", "x", motion),
        AbsoluteDriver("at", "a", "theta", motion),
        RelativeRotationDriver("rr", "a", "b", motion),
        PointPathDriver("pp", Point("a"), motion, motion),
        RelativeDisplacementDriver("rd", Point("a"), Point("b"), motion, motion),
    )
    assert system.labels == ["ax.x", "at.theta", "rr.theta", "pp.x", "pp.y", "rd.x", "rd.y"]
    assert [e.name for e in system.equations] == ["ax", "at", "rr", "pp", "rd"]
