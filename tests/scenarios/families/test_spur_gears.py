"""The spur gear pair's bodies as built: uniform discs of unit areal density (m = pi r^2,
J = m r^2 / 2 about the centre) whose guessed poses sit on their pivots, the output gear's at the
centre distance (r_in + r_out external, r_out - r_in internal). The kinematic closed form cannot see
the masses, and assembly would move a misplaced guess onto its pivot; the dynamics use them as built."""

from __future__ import annotations

import math

import pytest

import scenarios


@pytest.mark.parametrize(("variant", "distance"), [("", 0.05 + 0.15), ("/internal", 0.15 - 0.05)])
def test_the_gears_are_uniform_discs_on_their_pivots(variant: str, distance: float) -> None:
    scenario = scenarios.build("spur_gears" + variant)
    bodies = {body.name: body for body in scenario.bodies}
    for name, radius, centre in (("gear_in", 0.05, 0.0), ("gear_out", 0.15, distance)):
        body = bodies[name]
        mass = math.pi * radius**2
        assert body.mass == pytest.approx(mass, rel=1e-15)
        assert body.inertia == pytest.approx(mass * radius**2 / 2, rel=1e-15)
        assert body.guess[:2] == pytest.approx((centre, 0.0), abs=1e-15)


@pytest.mark.parametrize("variant", ["", "/internal"])
def test_the_guessed_poses_are_the_closed_form_s_at_the_start(variant: str) -> None:
    from scenarios.closed_form import exact

    scenario = scenarios.build("spur_gears" + variant, overrides={"theta0": 0.4})
    start = exact(scenario, [0.0])
    for body in ("gear_in", "gear_out"):
        pose = start.select((body,)).position
        assert pose is not None
        assert scenario.body(body).guess == pytest.approx(tuple(pose[0, 0]), abs=1e-15), body


@pytest.mark.parametrize("mesh", ["external", "internal"])
def test_the_joints_driver_and_description_are_named_as_the_family_says(mesh: str) -> None:
    """A joint's or driver's name names its force column in every engine's output; the description
    is what the catalogue lists."""
    scenario = scenarios.build("spur_gears", overrides={"mesh": mesh, "radius_out": 0.15})
    assert [joint.name for joint in scenario.joints] == ["pivot_in", "pivot_out", "mesh"]
    (driver,) = scenario.drivers
    assert (driver.name, driver.body, driver.coordinate) == ("drive", "gear_in", "theta")
    assert scenario.description == f"spur gear pair, {mesh} mesh, fixed centres"


def test_an_internal_ring_no_larger_than_its_pinion_is_refused_with_both_radii() -> None:
    from scenarios.scenario import ScenarioError

    with pytest.raises(ScenarioError) as refused:
        scenarios.build("spur_gears/internal", overrides={"radius_in": 0.05, "radius_out": 0.05})
    assert str(refused.value) == "spur_gears: an internal mesh needs radius_out > radius_in, got 0.05 <= 0.05"
