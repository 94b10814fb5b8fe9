"""The joints' residuals at hand-worked configurations, their row names, and the equation's name.

The derivative tests check C_q and Q_d against differences of C; they cannot see C itself wrong in a
way consistent with its own derivatives (a coefficient doubled, a normal built wrongly on a non-unit
axis, a length squared as 2 L). These values come from the geometry, worked by hand.
"""

from __future__ import annotations

import math

import numpy as np

from scenarios import GROUND, Ground, Point, Prismatic, Revolute, RevoluteRevolute
from tests.support.constraint_systems import residual, system_of


def test_a_ground_joint_is_the_offset_of_each_coordinate_from_its_pose() -> None:
    joint = Ground("g", "a", (1.0, 2.0, 0.5))
    np.testing.assert_allclose(
        residual(joint, {"a": (1.5, 1.0, 0.25)}), [0.5, -1.0, -0.25], rtol=0, atol=1e-15
    )


def test_a_revolute_joint_is_the_gap_between_its_two_pins() -> None:
    # a at (1, 0) turned by 90 degrees: its local (1, 0) is at (1, 1); b's local (0, 2) at (0, 2) + (0.5, 0)
    joint = Revolute("r", Point("a", (1.0, 0.0)), Point("b", (0.0, 2.0)))
    c = residual(joint, {"a": (1.0, 0.0, math.pi / 2), "b": (0.5, 0.0, 0.0)})
    np.testing.assert_allclose(c, [1.0 - 0.5, 1.0 - 2.0], rtol=0, atol=1e-15)


def test_a_slider_off_an_inclined_line_has_its_distance_from_the_line_as_normal_residual() -> None:
    """The line through the origin along (3, 4) (not a unit vector) is on the ground: a slider whose
    point is at (4, -3) is 5 from it, on the side of -(-4, 3)/5; a slider at (6, 8) is on it."""
    joint = Prismatic("p", Point(GROUND, (0.0, 0.0)), Point("a", (0.0, 0.0)), axis=(3.0, 4.0))
    off, on = residual(joint, {"a": (4.0, -3.0, 0.0)}), residual(joint, {"a": (6.0, 8.0, 0.0)})
    # h . (r_i - r_j), h = (-4, 3)/5: (-4 * (0 - 4) + 3 * (0 + 3)) / 5 = 5
    np.testing.assert_allclose(off, [0.0, 5.0], rtol=0, atol=1e-14)
    np.testing.assert_allclose(on, [0.0, 0.0], rtol=0, atol=1e-14)


def test_a_slider_on_a_turned_body_measures_across_the_body_fixed_axis() -> None:
    """Body a carries the axis (3, 4)/5 and is turned by 90 degrees: the axis points along (-4, 3)/5
    and its normal along (-3, -4)/5. b's point at (3, 4) from a's is 5 across it; the relative angle
    row is theta_a - theta_b - angle."""
    joint = Prismatic("p", Point("a", (0.0, 0.0)), Point("b", (0.0, 0.0)), axis=(3.0, 4.0), angle=1.0)
    c = residual(joint, {"a": (1.0, 1.0, math.pi / 2), "b": (4.0, 5.0, 0.25)})
    # h . (r_a - r_b) = (-3 * (1 - 4) - 4 * (1 - 5)) / 5 = (9 + 16) / 5
    np.testing.assert_allclose(c, [math.pi / 2 - 0.25 - 1.0, 5.0], rtol=0, atol=1e-14)


def test_a_distance_link_is_the_difference_of_the_squared_lengths() -> None:
    """Points 5 apart (a 3-4-5 triangle) on a link of length 3: 25 - 9."""
    joint = RevoluteRevolute("rr", Point("a", (1.0, 0.0)), Point("b", (0.0, 0.0)), 3.0)
    c = residual(joint, {"a": (0.0, 0.0, 0.0), "b": (-2.0, -4.0, 0.0)})
    np.testing.assert_allclose(c, [25.0 - 9.0], rtol=0, atol=1e-13)


def test_each_row_is_named_after_its_joint_and_what_it_constrains() -> None:
    system = system_of(
        Ground("g", "a", (0.0, 0.0, 0.0)),
        Revolute("r", Point("a"), Point("b")),
        Prismatic("p", Point("b"), Point("c")),
        RevoluteRevolute("rr", Point("a"), Point("c"), 1.0),
    )
    assert system.labels == ["g.x", "g.y", "g.theta", "r.x", "r.y", "p.angle", "p.normal", "rr.length"]
    assert [e.name for e in system.equations] == ["g", "r", "p", "rr"]
