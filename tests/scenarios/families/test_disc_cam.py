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
