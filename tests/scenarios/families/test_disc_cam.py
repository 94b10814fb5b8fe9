"""The cam families' bodies and profile as built: the cam a uniform disc of unit areal density
(m = pi R^2, J = m R^2 / 2 about its centre), the lobed profile d(phi) = R + e cos(lobes phi) with
the `lobes` asked for, and a description that names the follower. The disc's closed form sees none
of these: the masses matter to the dynamics, the lobed profile has no closed form."""

from __future__ import annotations

import math

import numpy as np
import pytest

import scenarios

FAMILIES = {"cam_knife_edge": "knife-edge", "cam_roller": "roller", "cam_flat_face": "flat-face"}


@pytest.mark.parametrize("family", sorted(FAMILIES))
def test_the_cam_is_a_uniform_disc_and_the_description_names_the_follower(family: str) -> None:
    scenario = scenarios.build(family, overrides={"radius": 0.07})
    cam = scenario.body("cam")
    mass = math.pi * 0.07**2
    assert cam.mass == pytest.approx(mass, rel=1e-15)
    assert cam.inertia == pytest.approx(mass * 0.07**2 / 2, rel=1e-15)
    assert scenario.description == f"disc cam with a translating {FAMILIES[family]} follower"


@pytest.mark.parametrize("lobes", [2, 5])
def test_the_lobed_profile_has_the_lobes_asked_for(lobes: int) -> None:
    scenario = scenarios.build(
        "cam_knife_edge",
        overrides={"profile": "lobed", "lobes": lobes, "radius": 0.05, "eccentricity": 0.002},
    )
    (contact,) = scenario.cams
    for phi in np.linspace(0.0, 2 * math.pi, 13):
        assert contact.profile.radii(float(phi))[0] == pytest.approx(
            0.05 + 0.002 * math.cos(lobes * phi), abs=1e-15
        )


@pytest.mark.parametrize("family", sorted(FAMILIES))
def test_the_guessed_poses_are_the_disc_s_closed_form_at_the_start(family: str) -> None:
    from scenarios.closed_form import exact

    scenario = scenarios.build(family, overrides={"theta0": 0.6})
    start = exact(scenario, [0.0])
    for body in ("cam", "follower"):
        pose = start.select((body,)).position
        assert pose is not None
        assert scenario.body(body).guess == pytest.approx(tuple(pose[0, 0]), abs=1e-15), body


@pytest.mark.parametrize("family", sorted(FAMILIES))
def test_the_joints_and_driver_are_named_and_the_follower_slides_along_y(family: str) -> None:
    """A joint's or driver's name names its force column in every engine's output; the guide's axis
    is the unit y vector through the cam's centre (the closed forms' follower axis)."""
    scenario = scenarios.build(family)
    assert [joint.name for joint in scenario.joints] == ["pivot", "guide", "contact"]
    guide = scenario.joints[1]
    assert (guide.axis, guide.p_j.local) == ((0.0, 1.0), (0.0, 0.0))  # type: ignore[union-attr]
    (driver,) = scenario.drivers
    assert (driver.name, driver.body, driver.coordinate) == ("cam_drive", "cam", "theta")


def test_the_lobed_knife_edge_s_guess_touches_the_profile_on_the_follower_s_axis() -> None:
    """The follower's axis (world +y) meets the cam at the cam-frame angle pi/2 - theta0; a knife
    edge there touches a lobed profile at d(pi/2 - theta0) = R + e cos(lobes (pi/2 - theta0))."""
    theta0, lobes = 0.3, 3
    scenario = scenarios.build(
        "cam_knife_edge",
        overrides={
            "profile": "lobed",
            "lobes": lobes,
            "radius": 0.05,
            "eccentricity": 0.002,
            "theta0": theta0,
        },
    )
    height = 0.05 + 0.002 * math.cos(lobes * (math.pi / 2 - theta0))
    assert scenario.body("follower").guess == pytest.approx((0.0, height, 0.0), abs=1e-15)


def test_the_eccentricity_may_be_zero_and_must_stay_below_the_radius() -> None:
    from scenarios.scenario import ScenarioError

    centred = scenarios.build("cam_knife_edge", overrides={"radius": 0.05, "eccentricity": 0.0})
    assert centred.body("follower").guess == pytest.approx((0.0, 0.05, 0.0), abs=1e-15)
    with pytest.raises(ScenarioError) as refused:
        scenarios.build("cam_knife_edge", overrides={"radius": 0.05, "eccentricity": 0.05})
    assert str(refused.value) == "cam_knife_edge: eccentricity must be in [0, radius), got 0.05"


def test_the_contact_s_guess_is_the_closed_form_s_contact_angle_at_the_start() -> None:
    """A knife edge on the y axis touches the disc where the axis meets it: at the world angle
    pi/2, the cam-frame angle pi/2 - theta0 (the closed form's `contact.phi` at t = 0)."""
    from scenarios.closed_form import exact

    scenario = scenarios.build("cam_knife_edge", overrides={"theta0": 0.6})
    (contact,) = scenario.cams
    phi = exact(scenario, [0.0]).extras["contact.phi"][0]
    assert contact.phi_guess == pytest.approx(phi, abs=1e-12)  # type: ignore[union-attr]


def test_the_follower_is_a_light_slider() -> None:
    """0.2 kg and 1e-4 kg m^2, whatever the cam's size (the dynamics use them as built)."""
    follower = scenarios.build("cam_roller").body("follower")
    assert (follower.mass, follower.inertia) == (0.2, 1e-4)
