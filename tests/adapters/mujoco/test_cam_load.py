"""MuJoCo's cam contact never reports a wrong answer as ok: a knife edge too blunt for the profile is
refused, the preload follows the follower's inertial force, and a lost contact fails the run. The
default cam model, the equivalent linkage, is right where the contact is refused."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from adapters.base import Setting
from adapters.mujoco.adapter import MujocoAdapter
from adapters.mujoco.cam_load import PRELOAD_FLOOR, PRELOAD_MARGIN, preload, pressure_angle
from adapters.mujoco.settings import own_regulariser
from scenarios.cams import KnifeEdgeCam
from scenarios.closed_form import exact
from scenarios.registry import build
from tests.support.bounds import held


def _contact(scenario) -> Setting:  # type: ignore[no-untyped-def]
    """The cam by contact: MuJoCo's own regulariser and tc = 4 steps (a hard contact loses it)."""
    return own_regulariser(MujocoAdapter().default_setting(scenario)).replace(cam_model="contact")


def _max_error(scenario, result) -> float:  # type: ignore[no-untyped-def]
    truth = exact(scenario, result.trajectory.times)
    body = scenario.output_bodies
    got, want = result.trajectory.select(body).position, truth.select(body).position
    return float(np.abs(got[..., :2] - want[..., :2]).max() / scenario.characteristic_length)


def test_pressure_angle_of_an_eccentric_disc_is_asin_e_over_r() -> None:
    # A radial follower on a disc of radius R offset by e: the largest pressure angle is asin(e/R).
    scenario = build("cam_knife_edge/stress_steep")
    (contact,) = scenario.cams
    assert isinstance(contact, KnifeEdgeCam)
    assert pressure_angle(contact) == pytest.approx(math.asin(0.045 / 0.05), abs=1e-4)


def test_steep_knife_edge_contact_is_unsupported_with_the_reason() -> None:
    scenario = build("cam_knife_edge/stress_steep")
    result = MujocoAdapter().run(scenario, _contact(scenario))
    assert result.status == "unsupported"
    assert "pressure angle reaches 64.2 deg" in result.message


def test_steep_knife_edge_as_its_linkage_is_right() -> None:
    scenario = build("cam_knife_edge/stress_steep", overrides={"steps": 40})
    result = MujocoAdapter().run(scenario)
    assert result.status == "ok" and result.setting.get("cam_model") == "linkage"
    # measured 1.26e-6 at the rule's step (1/2000 of the cam's turn, 3.1e-4 s; a tc of 4 steps)
    assert _max_error(scenario, result) < 2e-6


def test_mild_knife_edge_still_runs_and_matches_the_closed_form() -> None:
    scenario = build("cam_knife_edge", overrides={"steps": 40})
    result = MujocoAdapter().run(scenario, _contact(scenario))
    assert result.status == "ok", result.message
    # measured 1.03e-4: the contact's penetration at the rule's time constant (1.3e-3 s)
    assert _max_error(scenario, result) < 2e-4


def test_preload_is_sized_by_the_roller_followers_largest_inertial_force() -> None:
    # Roller centre at e cos(a) + sqrt(rho^2 - e^2 sin^2 a), rho = R + r: its largest |d2/da2| is
    # e + e^2 / rho (at a = 0); the follower's mass is 0.2 kg.
    omega, e, rho, mass = 300.0, 0.01, 0.05 + 0.02, 0.2
    scenario = build("cam_roller", overrides={"omega": omega})
    assert preload(scenario) == pytest.approx(PRELOAD_MARGIN * mass * (e + e * e / rho) * omega**2, rel=1e-4)
    assert preload(build("cam_roller")) == PRELOAD_FLOOR  # at 10 rad/s: 200 x 0.23 N is below the floor


@pytest.mark.parametrize(
    ("name", "omega", "measured"),
    [
        ("cam_roller", 300.0, 9.8e-5),
        ("cam_roller", 1000.0, 9.8e-5),
        ("cam_flat_face", 300.0, 6.2e-5),
        ("cam_knife_edge", 300.0, 6.2e-5),
    ],
)
def test_fast_cams_keep_their_contact_with_the_error_of_a_slow_one(
    name: str, omega: float, measured: float
) -> None:
    """The step, the time constant and the preload all scale with the speed, so the contact's error
    is the same at every speed from 30 rad/s up (cam_roller: 9.8e-5 of its length at 30 to 3000)."""
    scenario = build(name, overrides={"omega": omega})
    result = MujocoAdapter().run(scenario, _contact(scenario))
    assert result.status == "ok", result.message
    held([_max_error(scenario, result)], [measured], ("position",))


def test_an_undersized_preload_loses_the_contact() -> None:
    # 100 N against an inertial force of 0.2 kg * 0.0114 m * 300^2 = 206 N: the follower lifts off.
    scenario = build("cam_roller", overrides={"omega": 300.0})
    adapter = MujocoAdapter()
    result = adapter.run(scenario, _contact(scenario).replace(preload=100.0))
    assert result.status == "failed"
    assert "contact lost" in result.message


def test_scenes_without_cams_have_no_contact_pipeline() -> None:
    adapter = MujocoAdapter()
    plain = build("slider_crank")
    model = adapter.build(plain, adapter.default_setting(plain)).model
    assert model.opt.disableflags & mujoco.mjtDisableBit.mjDSBL_CONTACT
    cam = build("cam_roller")
    model = adapter.build(cam, _contact(cam)).model
    assert not model.opt.disableflags & mujoco.mjtDisableBit.mjDSBL_CONTACT
    model = adapter.build(cam, adapter.default_setting(cam)).model  # the linkage has no contact
    assert model.opt.disableflags & mujoco.mjtDisableBit.mjDSBL_CONTACT


@pytest.mark.parametrize("name", ["cam_knife_edge", "cam_roller", "cam_flat_face"])
def test_linkage_cam_model_matches_the_closed_form(name: str) -> None:
    scenario = build(name, overrides={"steps": 40})
    result = MujocoAdapter().run(scenario, Setting.of("RK4", cam_model="linkage", dt=1e-4))
    assert result.status == "ok", result.message
    assert _max_error(scenario, result) < 1e-8
