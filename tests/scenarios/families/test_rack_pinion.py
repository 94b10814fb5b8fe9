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
