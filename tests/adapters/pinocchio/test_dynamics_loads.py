"""The Pinocchio model of a free dynamic scenario: its loads as joint torques against finite
differences of their potentials and virtual work, its mass matrix against Pinocchio's own inverse
dynamics, and its gravity."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pinocchio as pin
import pytest

import scenarios
from adapters.pinocchio import PinocchioAdapter
from adapters.pinocchio.adapter import Built
from adapters.pinocchio.loads import Loads
from scenarios.bodies import GROUND, Point
from scenarios.forces import AppliedForce, RotationalSpringDamper, SpringDamper
from scenarios.motions import Constant
from scenarios.scenario import Scenario


def built(scenario: Scenario) -> Built:
    adapter = PinocchioAdapter()
    model: Built = adapter.build(scenario, adapter.default_setting(scenario))
    return model


def state(model: Built, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """A configuration near the start and an arbitrary joint velocity."""
    rng = np.random.default_rng(seed)
    assert model.start is not None
    q = model.start[1] + 0.1 * rng.standard_normal(model.pm.model.nq)
    return q, rng.standard_normal(model.pm.model.nv)


def point_position(model: Built, point: Point, q: np.ndarray) -> np.ndarray:
    """The point's global position from the scenario's own body pose (not Pinocchio's frame)."""
    m = model.pm.model
    data = m.createData()
    pin.forwardKinematics(m, data, q)
    pin.updateFramePlacements(m, data)
    if point.body == GROUND:
        return np.asarray(point.local, dtype=float)
    origin = data.oMf[model.pm.frame_id[Point(point.body)]].translation[:2]
    angle = model.pm.angle(point.body, q)
    c, s = np.cos(angle), np.sin(angle)
    return origin + np.array(
        [c * point.local[0] - s * point.local[1], s * point.local[0] + c * point.local[1]]
    )


def gradient(f, q: np.ndarray, h: float = 1e-6) -> np.ndarray:  # type: ignore[no-untyped-def]
    return np.array([(f(q + h * e) - f(q - h * e)) / (2 * h) for e in np.eye(q.size)])


def test_a_spring_is_minus_the_gradient_of_its_energy() -> None:
    """Andrews' spring (k = 4530 N/m between body 3 and the ground): tau = -dV/dq."""
    scenario = scenarios.load("andrews_squeezer")
    model = built(scenario)
    spring = next(f for f in scenario.forces if isinstance(f, SpringDamper))
    q, _ = state(model, 1)

    def potential(q: np.ndarray) -> float:
        gap = point_position(model, spring.p_i, q) - point_position(model, spring.p_j, q)
        return 0.5 * spring.stiffness * (float(np.linalg.norm(gap)) - spring.free_length) ** 2

    tau = Loads(model.pm, (spring,)).generalized(0.0, q, np.zeros_like(q))
    np.testing.assert_allclose(tau, -gradient(potential, q), rtol=1e-7, atol=1e-7 * np.abs(tau).max())


def test_a_damper_opposes_the_rate_of_its_length() -> None:
    """tau_damper . v = -c l'^2 (the power it dissipates), with l' by finite differences."""
    scenario = scenarios.load("slider_crank_spring")
    model = built(scenario)
    spring = next(f for f in scenario.forces if isinstance(f, SpringDamper))
    damper = replace(spring, stiffness=0.0, damping=7.0)
    q, v = state(model, 2)

    def length(q: np.ndarray) -> float:
        return float(
            np.linalg.norm(point_position(model, spring.p_i, q) - point_position(model, spring.p_j, q))
        )

    rate = float(gradient(length, q) @ v)
    tau = Loads(model.pm, (damper,)).generalized(0.0, q, v)
    assert float(tau @ v) == pytest.approx(-7.0 * rate**2, rel=1e-7)


def test_a_torsion_spring_and_a_point_force_do_their_virtual_work() -> None:
    """A torsion spring between crank and rod: tau = -dV/dq; a force at the rod's end: tau . dq
    equals F . dr for any virtual displacement dq."""
    scenario = scenarios.load("slider_crank_spring")
    model = built(scenario)
    q, _ = state(model, 3)
    torsion = RotationalSpringDamper("torsion", "crank", "rod", 3.0, 0.0, 0.2)

    def potential(q: np.ndarray) -> float:
        twist = model.pm.angle("rod", q) - model.pm.angle("crank", q) - 0.2
        return 0.5 * 3.0 * twist**2

    tau = Loads(model.pm, (torsion,)).generalized(0.0, q, np.zeros_like(q))
    np.testing.assert_allclose(tau, -gradient(potential, q), rtol=1e-7, atol=1e-9)
    tip = Point("rod", (0.1, 0.02))
    force = AppliedForce("push", tip, Constant(2.0), Constant(-5.0))
    with_tip = replace(scenario, forces=(force,))
    model = built(with_tip)
    tau = Loads(model.pm, (force,)).generalized(0.0, q, np.zeros_like(q))
    jacobian = np.array([gradient(lambda z, k=k: point_position(model, tip, z)[k], q) for k in (0, 1)])
    np.testing.assert_allclose(tau, jacobian.T @ np.array([2.0, -5.0]), rtol=1e-7, atol=1e-9)


def test_the_mass_matrix_is_pinocchios_inverse_dynamics_on_a_branched_tree() -> None:
    """Andrews' tree branches at the ground into bodies that carry children; crba (the mass matrix
    constraintDynamics and forwardDynamics use) is right only if every subtree's joints are
    contiguous, as the adapter now adds them (depth first). Added breadth first, entries coupling
    a pivoted body with its child were off by 3e-7 of 7e-5, and Andrews' angles by 0.11 rad."""
    model = built(scenarios.load("andrews_squeezer"))
    m = model.pm.model
    q, _ = state(model, 4)
    data, zero = m.createData(), np.zeros(m.nv)
    columns = [pin.rnea(m, data, q, zero, e) - pin.rnea(m, data, q, zero, zero) for e in np.eye(m.nv)]
    np.testing.assert_allclose(pin.crba(m, m.createData(), q), np.array(columns).T, rtol=0, atol=1e-15)


def test_gravity_is_the_scenarios_in_the_plane_and_none_in_kinematic_scenes() -> None:
    dynamic = built(scenarios.load("four_bar_gravity")).pm.model.gravity.linear
    kinematic = built(scenarios.load("four_bar")).pm.model.gravity.linear
    np.testing.assert_array_equal(dynamic, [0.0, -9.81, 0.0])
    np.testing.assert_array_equal(kinematic, [0.0, 0.0, 0.0])
