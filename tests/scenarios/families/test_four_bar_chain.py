"""The four-bar chain as built: one driver, named `crank_drive`, swinging the crank's absolute
angle; pivots named loop by loop (a driver's or joint's name names its force column in every
engine's output) and a description that counts the loops; guessed poses that are the closed form's
at the start."""

from __future__ import annotations

import pytest

import scenarios
from scenarios.closed_form import exact


def test_the_crank_s_angle_is_driven_by_crank_drive() -> None:
    scenario = scenarios.build("four_bar_chain")
    (driver,) = scenario.drivers
    assert (driver.name, driver.body, driver.coordinate) == ("crank_drive", "crank", "theta")


def test_the_guessed_poses_are_the_closed_form_s_at_the_start() -> None:
    """Parallelograms: at t = 0 every rocker stands at theta0 and every coupler lies level."""
    scenario = scenarios.build("four_bar_chain", overrides={"loops": 3, "theta0": 1.2})
    start = exact(scenario, [0.0])
    for body in scenario.bodies:
        pose = start.select((body.name,)).position
        assert pose is not None
        assert body.guess == pytest.approx(tuple(pose[0, 0]), abs=1e-15), body.name


def test_the_pivots_and_description_are_named_loop_by_loop() -> None:
    scenario = scenarios.build("four_bar_chain", overrides={"loops": 2})
    names = [joint.name for joint in scenario.joints]
    assert names == ["O0", "A1", "B1", "O1", "A2", "B2", "O2"]
    assert scenario.description == "chain of 2 parallelogram four-bar loops sharing rockers, crank swinging"
