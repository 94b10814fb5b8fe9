"""The planetary train as built: its guessed poses are the closed form's at the start (the arm from
the sun's centre to the planet's, at theta0; the planet on the arm's end), and its joints, driver and
description are named as the family describes them (a joint's or driver's name names its force
column in every engine's output; the description is what the catalogue lists)."""

from __future__ import annotations

import pytest

import scenarios
from scenarios.closed_form import exact


def test_the_guessed_poses_are_the_closed_form_s_at_the_start() -> None:
    scenario = scenarios.build("planetary_gears", overrides={"theta0": 0.7})
    start = exact(scenario, [0.0])
    for body in ("arm", "planet"):
        pose = start.select((body,)).position
        assert pose is not None
        assert scenario.body(body).guess == pytest.approx(tuple(pose[0, 0]), abs=1e-15), body


def test_the_joints_driver_and_description_are_named_as_the_family_says() -> None:
    scenario = scenarios.build("planetary_gears")
    assert [joint.name for joint in scenario.joints] == ["arm_pivot", "planet_pivot", "mesh"]
    pivot = scenario.joints[0]
    assert (pivot.p_i.body, pivot.p_i.local) == ("ground", (0.0, 0.0))  # type: ignore[union-attr]
    (driver,) = scenario.drivers
    assert (driver.name, driver.body, driver.coordinate) == ("arm_drive", "arm", "theta")
    assert scenario.description == "planetary train: fixed sun, driven arm, one planet"
