"""The Drake adapter on every kinematic family it models, against the closed forms; its settings by
the rule (default, untuned, ladder) and the reasons it gives for what it does not model.

Bounds are Drake's measured maxima with a margin of about 2 (default setting: the rule's step,
1/1000 of the shortest period), over every output (the march starts ten steps before the first,
adapters.drake.simulation.RUN_IN)."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("pydrake", reason="Drake is not installed (pip install -e '.[drake]')")

import scenarios
from adapters import load
from adapters.drake import DrakeAdapter
from scenarios.closed_form import exact
from scenarios.scenario import Level
from scenarios.trajectory import Trajectory

LEVELS: tuple[Level, ...] = ("position", "velocity", "acceleration")
BOUNDS = {  # position (m, rad), velocity, acceleration at the default setting
    "slider_crank": (5e-5, 2e-3, 0.8),
    "slider_crank/offset": (5e-5, 2e-3, 0.8),
    "slider_crank/slider_drive": (1.3e-4, 1e-2, 5.5),
    "slider_crank/slider_drive_offset": (1.3e-4, 1e-2, 5.5),
    "four_bar": (2e-4, 3e-2, 8.0),
    "four_bar/crossed": (2e-4, 3e-2, 8.0),
    "four_bar_chain": (7e-6, 2e-4, 1.5e-3),
    "spur_gears": (1e-12, 1e-12, 1e-11),
    "spur_gears/internal": (1e-12, 1e-12, 1e-11),
    "planetary_gears": (1e-12, 1e-12, 1e-11),
}
UNSUPPORTED = {
    "rack_pinion": "coupler",
    "cam_knife_edge": "cam joint",
    "cam_roller/spline": "cam joint",
    "cam_flat_face": "cam joint",
}


def errors(scenario: scenarios.Scenario, trajectory: Trajectory) -> dict[str, float]:
    truth = exact(scenario, trajectory.times).select(trajectory.bodies)
    found: dict[str, float] = {}
    for level in LEVELS:
        ours, theirs = trajectory.level(level), truth.level(level)
        assert ours is not None and theirs is not None
        gap = np.abs(ours - theirs)
        found[level] = float(np.max(gap))
    return found


def run(name: str, **options: object) -> tuple[scenarios.Scenario, Trajectory]:
    adapter = DrakeAdapter()
    scenario = scenarios.build(name)
    result = adapter.run(scenario, adapter.default_setting(scenario).replace(**options))  # type: ignore[arg-type]
    assert result.status == "ok", result.message
    assert result.trajectory is not None
    return scenario, result.trajectory


def test_registered_under_its_name() -> None:
    adapter = load("drake")
    assert isinstance(adapter, DrakeAdapter)
    assert adapter.version().startswith("1.")


@pytest.mark.parametrize("name", sorted(BOUNDS))
def test_default_matches_the_closed_form(name: str) -> None:
    scenario, trajectory = run(name)
    assert trajectory.levels == LEVELS
    found = errors(scenario, trajectory)
    assert all(found[lv] < bound for lv, bound in zip(LEVELS, BOUNDS[name], strict=True)), found


def test_positions_converge_as_the_square_of_the_step() -> None:
    """SAP's step is first order in velocity, and the drive's lead makes the position error a h^2:
    a tenth of the step gives a hundredth of the error (measured 2.28e-5 -> 2.29e-7)."""
    scenario = scenarios.build("slider_crank")
    dt = float(DrakeAdapter().default_setting(scenario).get("dt"))
    coarse = errors(*run("slider_crank"))["position"]
    fine = errors(*run("slider_crank", dt=dt / 10))["position"]
    assert 60 < coarse / fine < 160, (coarse, fine)


def test_the_untuned_drive_lags_a_step_behind() -> None:
    """The untuned setting targets theta(t) instead of theta(t + h): the implicit PD then reaches the
    target a step late, an error of one step's travel (omega h = 6.3e-3 rad on the slider-crank)."""
    adapter = DrakeAdapter()
    scenario = scenarios.build("slider_crank")
    untuned = adapter.untuned_setting(scenario)
    assert untuned is not None and untuned.get("dt") == adapter.default_setting(scenario).get("dt")
    result = adapter.run(scenario, untuned)
    assert result.trajectory is not None
    omega_h = abs(float(scenario.parameter("omega"))) * float(untuned.get("dt"))
    lag = errors(scenario, result.trajectory)["position"]
    assert 0.5 * omega_h < lag < 1.5 * omega_h, (lag, omega_h)


def test_the_state_velocity_is_the_midpoint_value() -> None:
    """Read as the state, Drake's velocity after the step to t is the step's mean: it matches the
    closed form at t - h/2 far better than at t."""
    adapter = DrakeAdapter()
    scenario = scenarios.build("four_bar")
    setting = adapter.default_setting(scenario).replace(velocity="state")
    trajectory = adapter.run(scenario, setting).trajectory
    assert trajectory is not None
    h = float(setting.get("dt"))
    at_t = exact(scenario, trajectory.times).select(trajectory.bodies).velocity
    at_mid = exact(scenario, trajectory.times - h / 2).select(trajectory.bodies).velocity
    assert at_t is not None and at_mid is not None and trajectory.velocity is not None
    off = np.max(np.abs(trajectory.velocity - at_t))
    mid = np.max(np.abs(trajectory.velocity - at_mid))
    assert mid < off / 10, (mid, off)


def test_the_ladder_runs_the_step_down_from_the_default() -> None:
    adapter = DrakeAdapter()
    scenario = scenarios.build("four_bar")
    ladder = adapter.ladder(scenario)
    steps = [float(s.get("dt")) for s in ladder]
    assert adapter.default_setting(scenario) in ladder
    assert steps[:-1] == sorted(steps[:-1], reverse=True)


@pytest.mark.parametrize("name", sorted(UNSUPPORTED))
def test_what_drake_does_not_model_is_unsupported_with_the_reason(name: str) -> None:
    adapter = DrakeAdapter()
    scenario = scenarios.build(name)
    reason = adapter.supports(scenario)
    assert reason is not None and UNSUPPORTED[name] in reason
    assert adapter.run(scenario).status == "unsupported"


def test_a_body_on_a_ground_joint_stays_at_the_joint_s_pose() -> None:
    """A ground joint fixes its body at the joint's pose, away from the origin and turned here; a
    pendulum pinned on it swings under gravity. Drake's weld must hold the body at that pose (a weld
    at the world's origin would report (0, 0, 0))."""
    pose = (0.2, -0.1, 0.5)
    base = scenarios.Body("base", pose, mass=1.0, inertia=0.1)
    pin = (0.2 + 0.1 * np.cos(0.5), -0.1 + 0.1 * np.sin(0.5))
    bob = scenarios.Body("bob", (pin[0] + 0.2, pin[1], 0.0), mass=1.0, inertia=0.01, length=0.4)
    joints = (
        scenarios.Ground("fix", "base", pose),
        scenarios.Revolute("pivot", scenarios.Point("base", (0.1, 0.0)), scenarios.Point("bob", (-0.2, 0.0))),
    )
    scenario = scenarios.Scenario(
        "welded", "default", (base, bob), joints, (), 0.2, 4, 0.4, gravity=(0.0, -9.81), analysis="dynamic"
    )
    adapter = DrakeAdapter()
    result = adapter.run(scenario, adapter.default_setting(scenario))
    assert result.status == "ok" and result.trajectory is not None, result.message
    held = result.trajectory.select(("base",)).level("position")
    assert held is not None
    np.testing.assert_allclose(held[:, 0, :], np.tile(pose, (len(held), 1)), rtol=0, atol=1e-12)
