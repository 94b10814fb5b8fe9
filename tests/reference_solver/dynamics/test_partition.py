"""The coordinate partition (dynamics.partition) on mechanisms worked by hand, on the plain path.

A rod of length l and mass m pinned at its end to the ground (compound_pendulum, one link), its
angle theta from +x the independent coordinate: its centre is (l/2 cos theta, l/2 sin theta), and
about the pin (J_O = m l^2 / 3) gravity gives theta'' = -(3 g / (2 l)) cos theta. Two such links in
a chain, the first driven at constant speed: the drivers' power is the rate of T + V, which the
equations of motion give at any state as q'^T (M q'' - Q_e) (the joints' rows do no work)."""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import pytest

import scenarios
from reference_solver.dynamics.partition import driver_power
from reference_solver.errors import ConvergenceError
from scenarios import Scenario
from tests.support.partitioned_scenes import counted, driven_chain, ode_of, rocked_chain

G, L = 9.81, 0.5
THETA = 2
"""The rod's angle column."""


def rod() -> Scenario:
    return scenarios.build("compound_pendulum", overrides={"links": 1, "theta0": 0.3})


def rod_centre(theta: float) -> np.ndarray:
    return np.array([0.5 * L * math.cos(theta), 0.5 * L * math.sin(theta), theta])


def test_the_rod_s_independent_coordinate_is_its_angle() -> None:
    """Scaled C_q = [[1, 0, sin/2], [0, 1, -cos/2]] (l = L): x and y are the best block."""
    ode, _ = ode_of(rod())
    np.testing.assert_array_equal(ode.independent, [THETA])
    np.testing.assert_array_equal(ode.dependent, [0, 1])


def test_the_chain_s_independent_coordinates_leave_a_regular_square_block() -> None:
    ode, system = ode_of(driven_chain())
    assert ode.size == 1  # two links less four pin rows and the driver's row
    jac = system.jacobian(ode.q, 0.0)
    assert np.linalg.matrix_rank(jac[:, ode.dependent]) == system.size == 5


@pytest.mark.parametrize(("theta", "omega"), [(0.7, 1.3), (-2.0, -0.4)])
def test_the_rod_s_state_and_rates_are_the_closed_form(theta: float, omega: float) -> None:
    ode, _ = ode_of(rod(), [THETA])
    y = np.array([theta, omega, 5.0, 6.0, 7.0])
    s = ode.state(0.25, y)
    c, si = math.cos(theta), math.sin(theta)
    alpha = -1.5 * G / L * c
    np.testing.assert_allclose(s.q, rod_centre(theta), rtol=0, atol=1e-15)
    np.testing.assert_allclose(s.qd, [-0.5 * L * si * omega, 0.5 * L * c * omega, omega], rtol=0, atol=1e-15)
    wanted = [-0.5 * L * (si * alpha + c * omega**2), 0.5 * L * (c * alpha - si * omega**2), alpha]
    np.testing.assert_allclose(s.qdd, wanted, rtol=0, atol=1e-13)
    # gravity does no applied work (it is in V), nothing dissipates, no driver
    np.testing.assert_allclose(ode.rates(0.25, y), [omega, alpha, 0.0, 0.0, 0.0], rtol=0, atol=1e-13)
    ode.rates(0.5, y)
    assert ode.evaluations == 2  # each right-hand side counted once


def test_newton_reaches_round_off_where_the_start_is_already_within_1e_12() -> None:
    """A move of 1e-13 rad misses the constraints by 5e-14 of L: within STALLED, above RESIDUAL."""
    ode, _ = ode_of(rod(), [THETA])
    theta = float(ode.q[THETA]) + 1e-13
    q, jac = ode.positions(0.0, np.array([theta]))
    np.testing.assert_allclose(q, rod_centre(theta), rtol=0, atol=2e-16)
    np.testing.assert_allclose(
        jac[:, THETA], [-0.5 * L * math.sin(theta), 0.5 * L * math.cos(theta)], atol=1e-16
    )


def test_an_unreachable_independent_coordinate_is_a_convergence_error_naming_time_and_residual() -> None:
    """The rod's centre cannot be 0.3 m right of its pin (it is 0.25 m long to the centre)."""
    ode, system = ode_of(rod(), [0])
    calls = counted(system)
    with pytest.raises(ConvergenceError) as caught:
        ode.positions(0.125, np.array([0.3]))
    message = str(caught.value)
    assert message.startswith("compound_pendulum: the dependent coordinates did not converge at t=0.125 ")
    assert message.endswith(")") and "(constraint residual " in message
    assert caught.value.time == 0.125 and len(calls) == 12
    assert caught.value.q is not None and caught.value.q[0] == 0.3  # the last iterate, x as asked


@pytest.mark.parametrize(("scenario", "independent"), [(rod, 0), (driven_chain, 3), (rocked_chain, 3)])
def test_the_tangent_predictor_from_the_anchor_saves_one_newton_iteration(
    scenario: Callable[[], Scenario], independent: int
) -> None:
    """From the anchor, a move of 1e-4 in an x (the rod's, or a driven chain's second link's, whose
    angle then follows nonlinearly) starts Newton within O(1e-8) of the solution: two evaluations,
    the second at round-off (measured 4e-8, then 2e-16). Without the predictor, or with it the
    wrong way, the start misses by O(1e-4): three (measured 2e-4, 4e-8, 2e-16)."""
    ode, system = ode_of(scenario(), [independent])
    y = np.concatenate([ode.q[ode.independent], np.zeros(4)])
    ode.anchor(0.0, y)
    calls = counted(system)
    moved = y[:1] + 1e-4
    q, _ = ode.positions(0.0, moved)
    assert len(calls) == 2
    ode.anchor(0.0, np.concatenate([moved, np.zeros(4)]))
    assert len(calls) == 2  # the anchor at the last evaluation solves nothing again
    assert np.max(np.abs(system.residual(q, 0.0) / system.row_scales)) <= 1e-14


def test_the_anchor_becomes_newton_s_start() -> None:
    ode, _ = ode_of(rod(), [THETA])
    ode.positions(0.0, np.array([0.4]))
    ode.anchor(0.5, np.array([1.1, 0.0]))
    start, jac, factors, _ = ode.start
    np.testing.assert_allclose(start, rod_centre(1.1), rtol=0, atol=1e-15)
    np.testing.assert_allclose(jac[:, THETA], [-0.5 * L * math.sin(1.1), 0.5 * L * math.cos(1.1)], atol=1e-15)
    assert factors is not None and ode.t == 0.5
    ode.restart(rod_centre(0.2))
    assert ode.start[2] is None and np.isnan(ode.t)
    np.testing.assert_array_equal(ode.start[0], rod_centre(0.2))


@pytest.mark.parametrize("scenario", [driven_chain, rocked_chain])
def test_the_driver_s_power_is_the_rate_of_the_mechanical_energy(scenario: Callable[[], Scenario]) -> None:
    """q'^T (M q'' - Q_e) = -lambda^T C_q q' (the equations of motion), and the joints' rows give
    C_q q' = 0: what is left is the driver's row."""
    ode, system = ode_of(scenario())
    rng = np.random.default_rng(3)
    for _ in range(3):
        y = np.concatenate(
            [ode.q[ode.independent] + 0.1 * rng.uniform(-1, 1, 1), rng.uniform(-3, 3, 1), np.zeros(3)]
        )
        s = ode.state(0.05, y)
        rate = float(s.qd @ (ode.mass * s.qdd - s.loads.generalized))
        assert abs(rate) > 0.1
        assert driver_power(system, s) == pytest.approx(rate, rel=1e-12)
        assert ode.rates(0.05, y)[-1] == pytest.approx(rate, rel=1e-12)


def test_a_partition_without_a_dependent_block_is_conditioned_as_well_as_can_be() -> None:
    body = scenarios.Body("b", (0.0, 0.0, 0.0), mass=1.0, inertia=0.1)
    free = Scenario("free", "default", (body,), (), (), 1.0, 1, 1.0, analysis="dynamic")
    ode, system = ode_of(free)
    np.testing.assert_array_equal(ode.independent, [0, 1, 2])
    assert ode.conditioning(system.jacobian(ode.q, 0.0)) == 1.0
