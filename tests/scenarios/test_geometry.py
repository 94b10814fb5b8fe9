"""Body points in world coordinates, against values worked by hand."""

from __future__ import annotations

import math

import pytest

from scenarios.geometry import compose, rotate, world_point


def test_rotation_by_a_quarter_turn() -> None:
    assert rotate(math.pi / 2, (1.0, 0.0)) == pytest.approx((0.0, 1.0), abs=1e-16)
    assert rotate(math.pi, (0.3, -0.2)) == pytest.approx((-0.3, 0.2), abs=1e-16)


def test_a_body_point_in_world_coordinates() -> None:
    # a link whose frame sits at (1, 2) turned by 30 degrees; its tip 0.5 along its x axis
    x, y = world_point((1.0, 2.0, math.pi / 6), (0.5, 0.0))
    assert (x, y) == pytest.approx((1.0 + 0.5 * math.sqrt(3) / 2, 2.0 + 0.25), abs=1e-15)


def test_composed_poses_add_angles_and_carry_the_offset() -> None:
    pose = compose((1.0, 0.0, math.pi / 2), (2.0, 0.0, 0.25))
    assert pose == pytest.approx((1.0, 2.0, math.pi / 2 + 0.25), abs=1e-15)
