"""Every force element's generalized force against finite differences, on many random states:
conservative parts against -dV/dq, dampers against -dR/dq_dot with R = c l_dot^2 / 2 (half the
dissipated power), applied loads against virtual work F . dr_P."""

from __future__ import annotations

import numpy as np
import pytest

from reference_solver.dynamics.loads import Loads
from reference_solver.layout import Layout
from scenarios import GROUND, Body, Constant, Harmonic, Point, Scenario
from scenarios.forces import AppliedForce, AppliedTorque, Force, RotationalSpringDamper, SpringDamper

BODIES = (
    Body("a", (0.1, 0.2, 0.3), mass=2.0, inertia=0.1),
    Body("b", (-0.2, 0.4, 1.1), mass=0.5, inertia=0.02),
)
CASES: dict[str, tuple[Force, ...]] = {
    "spring": (SpringDamper("s", Point("a", (0.3, -0.1)), Point("b", (-0.2, 0.15)), 120.0, 0.0, 0.25),),
    "spring_to_ground": (
        SpringDamper("s", Point(GROUND, (1.0, -0.5)), Point("b", (0.1, 0.2)), 80.0, 0.0, 0.4),
    ),
    "damper": (SpringDamper("s", Point("a", (0.3, -0.1)), Point("b", (-0.2, 0.15)), 0.0, 3.0, 0.25),),
    "torsion": (RotationalSpringDamper("r", "a", "b", 7.0, 0.0, 0.3),),
    "torsion_damper": (RotationalSpringDamper("r", GROUND, "b", 0.0, 1.5, 0.0),),
    "force": (AppliedForce("f", Point("a", (0.2, -0.3)), Constant(3.0), Harmonic(0.5, 2.0, 4.0)),),
    "torque": (AppliedTorque("t", "a", Harmonic(1.0, 0.5, 3.0), reaction="b"),),
}
RNG = np.random.default_rng(14)
STATES = [(RNG.uniform(-1, 1, 6), RNG.uniform(-2, 2, 6), float(RNG.uniform(0, 2))) for _ in range(40)]


def loads(forces: tuple[Force, ...], gravity: tuple[float, float] = (0.0, 0.0)) -> Loads:
    scenario = Scenario("t", "default", BODIES, (), (), 1.0, 1, 1.0, gravity=gravity, forces=forces)
    layout = Layout.of(scenario)
    return Loads(scenario, layout, np.array([2.0, 2.0, 0.1, 0.5, 0.5, 0.02]))


def gradient(f, x: np.ndarray, h: float = 1e-6) -> np.ndarray:  # type: ignore[no-untyped-def]
    out = np.empty_like(x)
    for k in range(x.size):
        e = np.zeros_like(x)
        e[k] = h
        out[k] = (f(x + e) - f(x - e)) / (2 * h)
    return out


@pytest.mark.parametrize("case", ["spring", "spring_to_ground", "torsion"])
def test_conservative_forces_are_minus_the_gradient_of_their_potential(case: str) -> None:
    element = loads(CASES[case])
    for q, qd, t in STATES:
        q_e = element(q, qd, t).generalized
        expected = -gradient(lambda x: element(x, qd, t).potential, q)  # noqa: B023
        np.testing.assert_allclose(q_e, expected, rtol=1e-7, atol=1e-7)


def test_gravity_is_minus_the_gradient_of_its_potential() -> None:
    element = loads((), gravity=(0.3, -9.81))
    for q, qd, t in STATES:
        expected = -gradient(lambda x: element(x, qd, t).potential, q)  # noqa: B023
        np.testing.assert_allclose(element(q, qd, t).generalized, expected, rtol=1e-8, atol=1e-8)


@pytest.mark.parametrize("case", ["damper", "torsion_damper"])
def test_dampers_are_minus_the_velocity_gradient_of_half_their_dissipation(case: str) -> None:
    element = loads(CASES[case])
    for q, qd, t in STATES:
        state = element(q, qd, t)
        expected = -gradient(lambda v: 0.5 * element(q, v, t).dissipation, qd)  # noqa: B023
        np.testing.assert_allclose(state.generalized, expected, rtol=1e-7, atol=1e-7)
        assert state.dissipation >= 0.0
        assert state.dissipation == pytest.approx(-state.generalized @ qd, rel=1e-12, abs=1e-12)


def point_position(q: np.ndarray, body: int, local: tuple[float, float]) -> np.ndarray:
    """R + A u, written out independently of the solver."""
    x, y, th = q[3 * body : 3 * body + 3]
    return np.array(
        [x + np.cos(th) * local[0] - np.sin(th) * local[1], y + np.sin(th) * local[0] + np.cos(th) * local[1]]
    )


def test_applied_force_does_the_virtual_work_of_a_force_at_its_point() -> None:
    (force,) = CASES["force"]
    assert isinstance(force, AppliedForce)
    element = loads(CASES["force"])
    for q, qd, t in STATES:
        f = np.array([force.fx.f(t), force.fy.f(t)])
        expected = gradient(lambda x: f @ point_position(x, 0, force.point.local), q)  # noqa: B023
        state = element(q, qd, t)
        np.testing.assert_allclose(state.generalized, expected, rtol=1e-8, atol=1e-8)
        assert state.applied_power == pytest.approx(state.generalized @ qd, rel=1e-12, abs=1e-12)


def test_applied_torque_does_the_virtual_work_of_a_relative_rotation() -> None:
    (torque,) = CASES["torque"]
    assert isinstance(torque, AppliedTorque)
    element = loads(CASES["torque"])
    for q, qd, t in STATES:
        expected = gradient(lambda x: torque.torque.f(t) * (x[2] - x[5]), q)  # noqa: B023
        state = element(q, qd, t)
        np.testing.assert_allclose(state.generalized, expected, rtol=1e-8, atol=1e-8)
        assert state.applied_power == pytest.approx(state.generalized @ qd, rel=1e-12, abs=1e-12)
