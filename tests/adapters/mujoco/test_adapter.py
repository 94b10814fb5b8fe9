"""MuJoCo adapter: every family against its closed form at the default setting, honest failures,
the exported model file, and a generic mechanism outside the catalogue (a tendon gear law).

The errors at the default (RK4 at the settings rule's step, equality time constant 128 steps with
the regulariser scaled by 1e-8, adapters.mujoco.weights, solimp 0.9999) are held within a factor 3
either way (MEASURED): linkages 1e-12..3e-10 m, relative accelerations 1e-12..3e-9; gears at
round-off; disc cams (by their linkage) near it. The chain of four-bars, at a coarser step for
its longer period, is the least accurate.
"""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

import scenarios
from adapters.base import Setting
from scenarios import (
    AbsoluteDriver,
    ConstantSpeed,
    Point,
    PointPathDriver,
    RevoluteRevolute,
    Scenario,
)
from scenarios.closed_form import exact
from tests.support.bounds import held
from tests.support.measured import measured_table
from tests.support.mechanisms import differential_train
from tests.support.mujoco.kinematic_errors import ADAPTER, errors
from tests.support.mujoco.scenes import DISC_SCENARIOS

MEASURED: dict[str, tuple[float, ...]] = measured_table("mujoco_defaults")
"""scenario: (position length [m], position angle [rad], velocity / max|v|, acceleration / max|a|)
at the default setting, measured with MuJoCo 4.0.1, held two-sided (tests.support.bounds)."""


@pytest.mark.parametrize("name", DISC_SCENARIOS)
def test_default_setting_matches_closed_forms(name: str) -> None:
    positions, rates = errors(name)
    held([*positions, *rates], MEASURED[name], ("length", "angle", "velocity", "acceleration"))


@pytest.mark.parametrize("name", [n for n in scenarios.catalogue() if n.endswith("/spline")])
def test_spline_cams_run_as_facets(name: str) -> None:
    # A polygon of facets (errors in test_cam_facets); a knife edge's as a sphere (test_cam_tip).
    assert ADAPTER.supports(scenarios.build(name)) is None


def test_instability_is_diverged_with_its_time_and_no_trajectory() -> None:
    # Explicit steps of a quarter revolution: the soft loop closure blows up.
    scenario = scenarios.build("slider_crank/slider_drive", overrides={"steps": 4})
    setting = Setting("Euler", ADAPTER.default_setting(scenario).options).replace(dt=1.0)
    result = ADAPTER.run(scenario, setting)
    assert result.status == "diverged" and result.trajectory is None
    assert result.failure_time is not None and math.isfinite(result.failure_time)
    assert any("unstable" in w for w in result.warnings)


def test_unknown_mode_fails_without_raising() -> None:
    scenario = scenarios.build("slider_crank")
    result = ADAPTER.run(scenario, Setting("Verlet", ADAPTER.default_setting(scenario).options))
    assert result.status == "failed" and "Verlet" in result.message


def test_export_reopens_in_mujoco_at_the_assembled_start(tmp_path: object) -> None:
    scenario = scenarios.build("four_bar")
    setting = ADAPTER.default_setting(scenario)
    path = f"{tmp_path}/four_bar.xml"
    ADAPTER.export(scenario, setting, path)
    model = mujoco.MjModel.from_xml_path(path)
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, model.key("start").id)
    mujoco.mj_forward(model, data)
    truth = exact(scenario, [0.0])
    assert truth.position is not None
    for k, body in enumerate(truth.bodies):
        site = data.site_xpos[model.site(body).id][:2]
        assert np.abs(site - truth.position[0, k, :2]).max() < 1e-7
    loop = data.efc_pos[data.efc_type == mujoco.mjtConstraint.mjCNSTR_EQUALITY]
    assert np.abs(loop).max() < 1e-7
    assert model.opt.integrator == mujoco.mjtIntegrator.mjINT_RK4


def _differential(rs: float, rp: float, w_sun: float, w_arm: float) -> Scenario:
    """A differential planetary train outside the catalogue: sun and arm both driven about the
    origin, planet on the arm. The gear law ties three hinges, so MuJoCo needs a tendon."""
    bodies, joints = differential_train(rs, rp)
    drivers = (
        AbsoluteDriver("sun_drive", "sun", "theta", ConstantSpeed(0.0, w_sun)),
        AbsoluteDriver("arm_drive", "arm", "theta", ConstantSpeed(0.0, w_arm)),
    )
    return Scenario("differential", "default", bodies, joints, drivers, 0.5, 100, rs + rp)


def test_a_three_joint_gear_law_becomes_a_tendon_and_is_exact() -> None:
    rs, rp, w_sun, w_arm = 0.06, 0.02, 7.0, 3.0
    scenario = _differential(rs, rp, w_sun, w_arm)
    xml = ADAPTER.build(scenario, ADAPTER.default_setting(scenario)).xml
    assert "<tendon>" in xml and "<equality>" in xml
    result = ADAPTER.run(scenario)
    assert result.status == "ok", result.message
    trajectory = result.trajectory
    assert trajectory is not None and trajectory.position is not None
    t = trajectory.times
    planet = trajectory.bodies.index("planet")
    # r_s (w_s - w_a) + r_p (w_p - w_a) = 0, and the planet's centre rides on the arm.
    w_planet = w_arm - rs / rp * (w_sun - w_arm)
    assert np.abs(trajectory.position[:, planet, 2] - w_planet * t).max() < 1e-11
    centre = (rs + rp) * np.stack([np.cos(w_arm * t), np.sin(w_arm * t)], axis=1)
    assert np.abs(trajectory.position[:, planet, :2] - centre).max() < 1e-12


def test_mechanisms_mujoco_has_no_equality_for_are_unsupported() -> None:
    base = scenarios.build("four_bar")
    link = RevoluteRevolute("B", Point("coupler", (0.05, 0.0)), Point("rocker", (0.0625, 0.0)), 0.0)
    joints = tuple(link if j.name == "B" else j for j in base.joints)
    reason = ADAPTER.supports(Scenario(**{**base.__dict__, "joints": joints}))
    assert reason is not None and "RevoluteRevolute" in reason
    path = PointPathDriver("path", Point("crank"), ConstantSpeed(0.0, 1.0), ConstantSpeed(0.0, 0.0))
    reason = ADAPTER.supports(Scenario(**{**base.__dict__, "drivers": (path,)}))
    assert reason is not None and "PointPathDriver" in reason
