"""Every force element's generalized force against finite differences, on many random states:
conservative parts against -dV/dq, dampers against -dR/dq_dot with R = c l_dot^2 / 2 (half the
dissipated power), applied loads against virtual work F . dr_P."""

from __future__ import annotations

import numpy as np
import pytest

from scenarios import GROUND, Constant, Point
from scenarios.forces import AppliedForce, AppliedTorque, RotationalSpringDamper, SpringDamper
from tests.support.force_elements import BODIES, CASES, STATES, loads


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


@pytest.mark.parametrize("case", ["damper", "torsion_damper", "torsion_damper_pair"])
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


# --- values in closed form: the derivative tests above hold for any consistent offset or factor ---
def test_gravity_pulls_each_body_s_centre_with_its_weight() -> None:
    q = np.array([0.1, 0.2, 0.3, -0.2, 0.4, 1.1])
    state = loads((), gravity=(0.3, -9.81))(q, np.zeros(6), 0.0)
    np.testing.assert_allclose(state.generalized, [0.6, -19.62, 0.0, 0.15, -4.905, 0.0], rtol=1e-15)
    assert state.potential == pytest.approx(-(0.6 * 0.1 - 19.62 * 0.2 + 0.15 * -0.2 - 4.905 * 0.4), rel=1e-15)
    assert state.applied_power == state.dissipation == 0.0


def test_a_spring_damper_from_a_ground_point_pulls_with_its_tension_along_the_line() -> None:
    """Point (0.1, 0) of body b at (0.2, 0.4), unturned: 0.5 m from the ground's origin along
    u = (0.6, 0.8), moving at (0.6, 0.8), so l' = 1: tension 80 (0.5 - 0.4) + 3 x 1 = 11 pulls the
    point by -11 u, whose moment about b's centre is 0.1 x (-8.8)."""
    spring = SpringDamper("s", Point(GROUND, (0.0, 0.0)), Point("b", (0.1, 0.0)), 80.0, 3.0, 0.4)
    q, qd = np.array([0.0, 0.0, 0.0, 0.2, 0.4, 0.0]), np.array([0.0, 0.0, 0.0, 0.6, 0.8, 0.0])
    state = loads((spring,))(q, qd, 0.0)
    np.testing.assert_allclose(state.generalized, [0.0, 0.0, 0.0, -6.6, -8.8, -0.88], rtol=1e-14, atol=1e-15)
    assert state.potential == pytest.approx(0.5 * 80.0 * 0.1**2, rel=1e-14)
    assert state.dissipation == pytest.approx(3.0, rel=1e-14)


@pytest.mark.parametrize("grounded", ["i", "j"])
def test_a_torsion_spring_damper_to_the_ground_turns_its_body_back_to_its_free_angle(grounded: str) -> None:
    """T = k (theta_j - theta_i - theta0) + c (omega_j - omega_i), +T on i and -T on j, the ground's
    angle and rate 0: with k = 7, theta0 = 0.3, c = 1.5, body a at 1.0 turning at 2 rad/s."""
    i, j = (GROUND, "a") if grounded == "i" else ("a", GROUND)
    element = RotationalSpringDamper("r", i, j, 7.0, 1.5, 0.3)
    q, qd = np.array([0.0, 0.0, 1.0, 0.0, 0.0, 0.0]), np.array([0.0, 0.0, 2.0, 0.0, 0.0, 0.0])
    state = loads((element,))(q, qd, 0.0)
    stretch, rate = (1.0 - 0.3, 2.0) if grounded == "i" else (-1.0 - 0.3, -2.0)
    torque = 7.0 * stretch + 1.5 * rate
    np.testing.assert_allclose(state.generalized, [0.0, 0.0, -torque if grounded == "i" else torque, 0, 0, 0])
    assert state.potential == pytest.approx(0.5 * 7.0 * stretch**2, rel=1e-15)
    assert state.dissipation == pytest.approx(1.5 * 4.0, rel=1e-15)


def test_a_torque_against_the_ground_does_work_at_its_body_s_rate() -> None:
    element = AppliedTorque("t", "b", Constant(2.5))
    state = loads((element,))(np.zeros(6), np.array([0.0, 0.0, 9.0, 0.0, 0.0, -3.0]), 0.0)
    np.testing.assert_allclose(state.generalized, [0.0, 0.0, 0.0, 0.0, 0.0, 2.5])
    assert state.applied_power == -7.5


def test_every_element_at_once_adds_up() -> None:
    """Q_e, potential, power and dissipation of all the cases together: the sums of each alone."""
    every = tuple(f for case in CASES.values() for f in case)
    for q, qd, t in STATES[:5]:
        alone = [loads(case)(q, qd, t) for case in CASES.values()]
        for order in (every, every[::-1]):  # an element that set a sum would undo those before it
            state = loads(order)(q, qd, t)
            total = sum(s.generalized for s in alone)
            np.testing.assert_allclose(state.generalized, total, rtol=1e-13, atol=1e-13)
            for field in ("potential", "applied_power", "dissipation"):
                expected = sum(getattr(s, field) for s in alone)
                assert getattr(state, field) == pytest.approx(expected, rel=1e-13)


def test_an_unknown_force_element_is_refused_by_its_type() -> None:
    with pytest.raises(TypeError, match=r"^no generalized force for Body$"):
        loads((BODIES[0],))(np.zeros(6), np.zeros(6), 0.0)  # type: ignore[arg-type]
