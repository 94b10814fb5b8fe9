"""The rack and pinion as built: the rack a 1 kg slider whose frame sits on the pitch line under
the pinion's centre (its mass loads only the guide: the driven kinematics cannot see it)."""

from __future__ import annotations

import pytest

import scenarios
from scenarios.bodies import GROUND
from scenarios.closed_form import exact


def test_the_rack_is_a_one_kilogram_slider_on_the_pitch_line() -> None:
    scenario = scenarios.build("rack_pinion", overrides={"radius": 0.04})
    rack = scenario.body("rack")
    assert rack.mass == 1.0
    assert rack.guess == pytest.approx((0.0, -0.04, 0.0), abs=1e-15)


def test_the_guide_s_origin_is_where_the_rack_starts() -> None:
    """The guide's ground point is the rack's frame at t = 0 (on the pitch line under the pinion's
    centre): the slide's travel counts from the start, radius * (theta - theta0)."""
    scenario = scenarios.build("rack_pinion", overrides={"radius": 0.04, "theta0": 0.3})
    guide = next(joint for joint in scenario.joints if joint.name == "guide")
    assert (guide.p_i.body, guide.p_i.local, guide.p_j.body) == ("rack", (0.0, 0.0), GROUND)
    start = exact(scenario, [0.0]).select(("rack",)).position[0, 0]
    assert guide.p_j.local == pytest.approx(tuple(start[:2]), abs=1e-15)


def test_the_guessed_poses_are_the_closed_form_s_at_the_start() -> None:
    scenario = scenarios.build("rack_pinion", overrides={"radius": 0.04, "theta0": 0.3})
    start = exact(scenario, [0.0])
    for body in ("pinion", "rack"):
        pose = start.select((body,)).position
        assert pose is not None
        assert scenario.body(body).guess == pytest.approx(tuple(pose[0, 0]), abs=1e-15), body


def test_the_joints_are_named_and_the_rack_slides_along_the_unit_x_axis() -> None:
    """A joint's name names its force column in every engine's output; the axes are unit vectors
    (the scenario's convention: an adapter may take an axis as given)."""
    scenario = scenarios.build("rack_pinion")
    joints = {joint.name: joint for joint in scenario.joints}
    assert list(joints) == ["pivot", "guide", "mesh"]
    assert joints["guide"].axis == (1.0, 0.0)  # type: ignore[union-attr]
    assert joints["mesh"].axis == (1.0, 0.0)  # type: ignore[union-attr]


def test_the_driver_and_description_are_named_as_the_family_says() -> None:
    scenario = scenarios.build("rack_pinion")
    (driver,) = scenario.drivers
    assert (driver.name, driver.body, driver.coordinate) == ("drive", "pinion", "theta")
    assert scenario.description == "pinion on fixed centre driving a sliding rack"
