"""MuJoCo's loads in free dynamics: every force of the vocabulary on an open chain (so no
constraint softness blurs them) against the native truth, the spring's tendon as the straight
line between its points; and what it cannot represent: a rotational spring on a loop closure, a cam
contact (its preload spring would be a force of its own)."""

from __future__ import annotations

import dataclasses

import mujoco
import numpy as np
import pytest

import scenarios
from adapters.mujoco.loads import site_name
from adapters.mujoco.tree import plan_tree
from reference_solver.dynamics import simulate
from scenarios.bodies import Point
from scenarios.forces import AppliedForce, AppliedTorque, RotationalSpringDamper, SpringDamper
from scenarios.geometry import world_point
from scenarios.motions import Constant, Harmonic
from tests.support.mujoco.truths import ADAPTER

LOADS = (
    RotationalSpringDamper("knee", "link_1", "link_2", stiffness=2.0, damping=0.05, free_angle=0.3),
    RotationalSpringDamper("hip", "link_1", "ground", stiffness=1.5, damping=0.02, free_angle=-0.2),
    AppliedTorque("motor", "link_2", Harmonic(0.0, 0.5, 7.0), reaction="link_1"),
    AppliedForce("push", Point("link_2", (0.25, 0.0)), Harmonic(0.0, 2.0, 5.0, 0.3), Constant(-1.0)),
    SpringDamper("spring", Point("link_1", (0.1, 0.05)), Point("ground", (0.3, 0.2)), 50.0, 0.5, 0.2),
)
"""Both signs of a hinge spring (the pair's second body the hinge's child, then its parent), a
time-varying torque reacted on another body, a time-varying force at a point, a spring-damper."""


def loaded_pendulum() -> scenarios.Scenario:
    scenario = scenarios.build("compound_pendulum", overrides={"t_end": 0.5, "steps": 25})
    return dataclasses.replace(scenario, forces=LOADS)


def test_every_load_on_an_open_chain_matches_the_native_truth() -> None:
    scenario = loaded_pendulum()
    expected = simulate(scenario, scenario.times(), rtol=1e-11).trajectory()
    result = ADAPTER.run(scenario)
    assert result.status == "ok", result.message
    got = result.trajectory
    assert got is not None and got.position is not None and got.acceleration is not None
    expected = expected.select(got.bodies)
    assert expected.position is not None and expected.acceleration is not None
    # measured 5.7e-12 m and 1.2e-9 m/s^2 with RK4 at 1e-4 s: the time-varying controls are set at
    # every RK4 stage's time, so the loads cost no order
    assert np.abs(got.position - expected.position).max() < 1e-10
    assert np.abs(got.acceleration - expected.acceleration).max() < 1e-7


def test_the_spring_is_the_straight_line_between_its_points() -> None:
    scenario = loaded_pendulum()
    spring = next(f for f in scenario.forces if isinstance(f, SpringDamper))
    built = ADAPTER.build(scenario, ADAPTER.default_setting(scenario))
    m = built.model
    d = mujoco.MjData(m)
    d.qpos[:] = built.qpos0 + np.array([0.4, -0.7])
    mujoco.mj_forward(m, d)
    pose = d.site_xpos[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_SITE, "link_1")]
    theta = built.theta[0].const + built.theta[0].coefs["pin_1"] * d.qpos[0]
    p_i = np.array(world_point((pose[0], pose[1], theta), spring.p_i.local))
    length = np.linalg.norm(p_i - np.array(spring.p_j.local))
    assert d.ten_length[0] == pytest.approx(length, rel=1e-14)
    assert site_name(spring.p_i) in {m.site(k).name for k in range(m.nsite)}


def test_a_rotational_spring_on_a_loop_closure_is_unsupported() -> None:
    scenario = scenarios.load("four_bar_gravity")
    closure = plan_tree(scenario).closures[0]
    spring = RotationalSpringDamper("spring", closure.p_i.body, closure.p_j.body, stiffness=1.0)
    result = ADAPTER.run(dataclasses.replace(scenario, forces=(spring,)))
    assert result.status == "unsupported"
    assert "not one tree hinge" in result.message


def test_a_cam_contact_in_free_dynamics_is_unsupported() -> None:
    scenario = dataclasses.replace(scenarios.load("cam_roller"), analysis="dynamic")
    setting = ADAPTER.default_setting(scenario).replace(cam_model="contact")
    result = ADAPTER.run(scenario, setting)
    assert result.status == "unsupported"
    assert "preload spring" in result.message
