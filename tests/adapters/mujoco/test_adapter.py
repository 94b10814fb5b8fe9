"""MuJoCo adapter: every family against its closed form at the default setting, honest failures,
the exported model file, and a generic mechanism outside the catalogue (a tendon gear law).

Bounds are a few times what MuJoCo 4.0 was measured to reach at the default (RK4, dt 1e-4,
solref 2 dt, solimp 0.9999; cams: contact solimp 0.99, 100 N preload):
slider-crank and four-bar positions 1.5e-8..3e-8 m, angles 5e-8..3e-7 rad; gears 1e-14 m, 2e-12 rad;
disc cams 1.3e-7..2.2e-7 m. Velocities are worse than positions (a soft constraint's velocity
error is its position error over its time constant) and accelerations carry an O(1) floor under
RK4 (the constraint's stabilising term), which the relative bounds below reflect.
"""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

import scenarios
from adapters.base import Setting
from adapters.mujoco import MujocoAdapter
from scenarios import (
    AbsoluteDriver,
    ConstantSpeed,
    Point,
    PointPathDriver,
    RevoluteRevolute,
    Scenario,
)
from scenarios.closed_form import exact
from tests.support.mechanisms import differential_train

ADAPTER = MujocoAdapter()

# family: (position length [m], position angle [rad], velocity / max|v|, acceleration / max|a|)
BOUNDS = {
    "slider_crank": (1e-7, 1e-6, 1e-4, 1e-2),
    "four_bar": (1e-7, 1e-6, 1e-4, 1e-2),
    "spur_gears": (1e-12, 1e-11, 5e-11, 1e-9),
    "planetary_gears": (1e-12, 1e-11, 5e-11, 1e-9),
    "rack_pinion": (1e-12, 1e-11, 5e-11, 1e-9),
    "cam_knife_edge": (5e-7, 1e-6, 3e-6, 1e-2),
    "cam_roller": (5e-7, 1e-6, 3e-6, 1e-2),
    "cam_flat_face": (5e-7, 1e-6, 3e-6, 1e-2),
    "four_bar_chain": (1e-7, 1e-6, 1e-4, 1e-2),
}
DISC_SCENARIOS = [n for n in scenarios.catalogue() if not n.endswith("/spline")]


def errors(name: str, setting: Setting | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Position errors (lengths, angles) and relative velocity and acceleration errors."""
    scenario = scenarios.build(name)
    result = ADAPTER.run(scenario, setting)
    assert result.status == "ok", result.message
    trajectory = result.trajectory
    assert trajectory is not None
    truth = exact(scenario, trajectory.times).select(trajectory.bodies)
    out = []
    omega = abs(float(scenario.parameter("omega")))
    for level in ("position", "velocity", "acceleration"):
        got, want = trajectory.level(level), truth.level(level)
        assert got is not None and want is not None
        error = np.abs(got - want)
        if level == "position":
            out += [error[..., :2].max(), error[..., 2].max()]
            continue
        # Relative to the level's size; accelerations at least omega |v| (zero at constant speed).
        size = np.abs(want).max()
        if level == "acceleration":
            size = max(size, omega * np.abs(truth.velocity).max())
        out.append(error.max() / size)
    return np.array(out[:2]), np.array(out[2:])


@pytest.mark.parametrize("name", DISC_SCENARIOS)
def test_default_setting_matches_closed_forms(name: str) -> None:
    positions, rates = errors(name)
    length, angle, velocity, acceleration = BOUNDS[name.split("/")[0]]
    assert positions[0] < length and positions[1] < angle
    assert rates[0] < velocity and rates[1] < acceleration


@pytest.mark.parametrize("name", [n for n in scenarios.catalogue() if n.endswith("/spline")])
def test_spline_cams_run_as_facets_or_are_refused_with_their_reason(name: str) -> None:
    # Roller and flat face: a polygon of facets (errors in test_cam_facets); a knife edge chatters.
    reason = ADAPTER.supports(scenarios.build(name))
    if name.startswith("cam_knife_edge"):
        assert reason is not None and "chatters" in reason
    else:
        assert reason is None


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
