"""The stacked constraint system on a small mechanism whose rows are worked by hand.

Bodies a and b, characteristic length L = 0.5. The joints: a grounded at (0.1, 0.2, 0.3) (rows
x - 0.1, y - 0.2, theta - 0.3) and a pin joining a's point (0.5, 0) to b's origin
(r_a + A(theta_a) (0.5, 0) - r_b); then the driver theta_b = f(t) = 0.5 + 0.4 cos(2 t). At
t = pi/6 (2 t = pi/3): f = 0.7, f' = -0.4 * 2 * sin(pi/3) = -0.4 sqrt(3), f'' = -0.4 * 4 / 2 = -0.8.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from reference_solver.system import ConstraintSystem, equation_for
from scenarios import AbsoluteDriver, Body, Ground, Harmonic, Point, Revolute, Scenario

L = 0.5
T = math.pi / 6
Q = np.array([0.3, -0.1, math.pi / 2, 0.2, 0.3, 1.0])  # a turned a quarter: its pin point is r_a + (0, 0.5)
QD = np.array([1.0, 2.0, 2.0, 0.0, 0.0, 5.0])


def _scenario(with_joints: bool = True) -> Scenario:
    return Scenario(
        family="hand_system",
        variant="default",
        bodies=(Body("a", (0.0, 0.0, 0.0)), Body("b", (0.0, 0.0, 0.0))),
        joints=(Ground("g", "a", (0.1, 0.2, 0.3)), Revolute("r", Point("a", (0.5, 0.0)), Point("b")))
        if with_joints
        else (),
        drivers=(AbsoluteDriver("d", "b", "theta", Harmonic(0.5, 0.4, 2.0)),),
        t_end=1.0,
        steps=1,
        characteristic_length=L,
    )


def test_the_rows_are_the_joints_then_the_drivers_with_their_length_scales() -> None:
    system = ConstraintSystem(_scenario())
    assert system.labels == ["g.x", "g.y", "g.theta", "r.x", "r.y", "d.theta"]
    np.testing.assert_array_equal(system.offsets, [0, 3, 5, 6])
    assert (system.size, system.unknowns) == (6, 6)
    np.testing.assert_array_equal(
        system.row_scales, [L, L, 1.0, L, L, 1.0]
    )  # L^1 for lengths, L^0 for angles
    np.testing.assert_array_equal(system.column_scales, [L, L, 1.0, L, L, 1.0])
    joints_only = ConstraintSystem(_scenario(), include_drivers=False)
    assert joints_only.labels == ["g.x", "g.y", "g.theta", "r.x", "r.y"]
    assert (joints_only.size, joints_only.unknowns) == (5, 6)


def test_c_its_jacobian_and_q_d_are_stacked_in_row_order() -> None:
    """C: g (0.3 - 0.1, -0.1 - 0.2, pi/2 - 0.3); r (0.3 + 0 - 0.2, -0.1 + 0.5 - 0.3); d 1 - 0.7.
    C_q: g the identity on a; r the identity on r_a, dA/dtheta (0.5, 0) = (-0.5, 0) on theta_a, minus
    the identity on r_b; d one on theta_b. Q_d: the pin's A(theta_a) (0.5, 0) theta_a'^2 = (0, 2) at
    theta_a' = 2, the driver's f'' = -0.8, the ground's 0."""
    system = ConstraintSystem(_scenario())
    c, jac, q_d = system.evaluate(Q, T, QD)
    np.testing.assert_allclose(c, [0.2, -0.3, math.pi / 2 - 0.3, 0.1, 0.1, 0.3], rtol=0, atol=1e-15)
    expected = np.array(
        [
            [1, 0, 0, 0, 0, 0],
            [0, 1, 0, 0, 0, 0],
            [0, 0, 1, 0, 0, 0],
            [1, 0, -0.5, -1, 0, 0],
            [0, 1, 0, 0, -1, 0],
            [0, 0, 0, 0, 0, 1],
        ]
    )
    np.testing.assert_allclose(jac, expected, rtol=0, atol=1e-15)
    np.testing.assert_allclose(q_d, [0, 0, 0, 0, 2.0, -0.8], rtol=0, atol=1e-15)
    np.testing.assert_array_equal(system.residual(Q, T), c)
    np.testing.assert_array_equal(system.jacobian(Q, T), jac)
    np.testing.assert_array_equal(system.q_d(Q, QD, T), q_d)


def test_without_rates_q_d_holds_only_the_drivers_time_terms() -> None:
    """With no qd given the rates are zero: the pin's centripetal term vanishes, f'' = -0.8 stays."""
    _, _, q_d = ConstraintSystem(_scenario()).evaluate(Q, T)
    np.testing.assert_allclose(q_d, [0, 0, 0, 0, 0, -0.8], rtol=0, atol=1e-15)


def test_c_t_is_minus_the_drivers_rate_and_zero_for_the_joints() -> None:
    """C_t of theta_b - f(t) is -f' = 0.4 sqrt(3)."""
    c_t = ConstraintSystem(_scenario()).c_t(T)
    np.testing.assert_allclose(c_t, [0, 0, 0, 0, 0, 0.4 * math.sqrt(3)], rtol=0, atol=1e-15)


def test_a_system_without_rows_has_an_empty_c_t() -> None:
    system = ConstraintSystem(_scenario(with_joints=False), include_drivers=False)
    assert system.size == 0 and system.c_t(T).shape == (0,)
    c, jac, q_d = system.evaluate(Q, T, QD)
    assert c.shape == (0,) and jac.shape == (0, 6) and q_d.shape == (0,)


def test_the_scaled_jacobian_measures_lengths_in_units_of_l() -> None:
    """D_r^-1 C_q D_c: a length row over a length column keeps its entry (L / L), a length row over
    an angle column is divided by L (the pin's -0.5 becomes -1), an angle row over a length column
    would be multiplied by L."""
    system = ConstraintSystem(_scenario())
    jac = np.arange(36.0).reshape(6, 6) + 1
    scaled = system.scaled_jacobian(jac)
    assert scaled[3, 2] == jac[3, 2] / L  # r.x over theta_a
    assert scaled[2, 0] == jac[2, 0] * L  # g.theta over x_a
    assert scaled[0, 0] == jac[0, 0] and scaled[5, 5] == jac[5, 5]
    scales = np.array([L, L, 1.0, L, L, 1.0])
    np.testing.assert_allclose(scaled, np.diag(1 / scales) @ jac @ np.diag(scales), rtol=1e-15)
    np.testing.assert_allclose(system.scaled_jacobian(system.jacobian(Q, T))[3, 2], -1.0, rtol=1e-15)


def test_a_constraint_of_no_known_kind_is_refused_by_name() -> None:
    class Weld:
        name = "w"

    layout = ConstraintSystem(_scenario()).layout
    with pytest.raises(TypeError) as caught:
        equation_for(Weld(), layout)  # type: ignore[arg-type]
    assert str(caught.value) == "no equations for constraint type Weld"
    assert caught.value.__cause__ is None and caught.value.__suppress_context__
