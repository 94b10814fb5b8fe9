"""Newton's exits and arithmetic where the mutation run (docs/mutation.md) found them unchecked: a
start whose residual is not finite stops at once; the iteration count, the strict tolerances, the
unconverged result's fields, a singular Jacobian, an empty system, and the backtracking's halving,
each on a one-unknown system whose iterates are worked by hand."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import scenarios
from reference_solver import ConstraintSystem
from reference_solver.newton import NewtonSettings, newton
from reference_solver.newton import _round_off as newton_round_off
from scenarios.closed_form import exact
from tests.support.newton_systems import OneUnknown


def test_a_non_finite_start_is_returned_unconverged_at_once() -> None:
    system = ConstraintSystem(scenarios.build("slider_crank"))
    start = np.full(system.unknowns, np.nan)
    result = newton(system, start, 0.0, NewtonSettings())
    assert result.converged is False and result.iterations == 0 and result.factors is None
    assert math.isnan(result.residual)
    assert result.q.shape == start.shape and np.isnan(result.q).all()


def linear() -> OneUnknown:
    return OneUnknown(lambda q: q - 0.5, lambda q: 1.0)


def test_a_linear_constraint_row_converges_on_the_second_iteration_with_its_residual() -> None:
    # iteration 0: C = -0.5, step to 0.5; iteration 1: C = 0 but the step was 0.5; iteration 2: done
    result = newton(linear(), np.array([0.0]), 0.0, NewtonSettings())  # type: ignore[arg-type]
    assert result.converged is True and result.iterations == 2 and result.residual == 0.0
    assert result.q[0] == 0.5 and result.factors is not None


def test_the_tolerances_are_strict_and_an_unconverged_result_says_how_far_it_got() -> None:
    for settings in (NewtonSettings(residual_tolerance=0.0), NewtonSettings(step_tolerance=0.0)):
        result = newton(linear(), np.array([0.0]), 0.0, dataclasses.replace(settings, max_iterations=3))  # type: ignore[arg-type]
        assert result.converged is False and result.iterations == 3 and result.residual == 0.0
    rootless = OneUnknown(lambda q: q * q + 1.0, lambda q: 2.0 * q)  # no real root
    result = newton(rootless, np.array([0.3]), 0.0, NewtonSettings(max_iterations=4))  # type: ignore[arg-type]
    assert result.converged is False and result.iterations == 4
    assert result.residual == pytest.approx(result.q[0] ** 2 + 1.0, rel=1e-12)  # at the last iterate


def test_a_singular_jacobian_stops_at_once() -> None:
    flat = OneUnknown(lambda q: 1.0, lambda q: 0.0)
    result = newton(flat, np.array([0.0]), 0.0, NewtonSettings())  # type: ignore[arg-type]
    assert result.converged is False and result.iterations == 0 and result.residual == 1.0


def test_an_empty_system_has_residual_zero_and_no_factors_to_step_with() -> None:
    empty = OneUnknown(lambda q: 0.0, lambda q: 0.0)
    empty.row_scales, empty.column_scales = np.zeros(0), np.zeros(0)
    empty.evaluate = lambda q, t: (np.zeros(0), np.zeros((0, 0)), None)  # type: ignore[method-assign]
    result = newton(empty, np.zeros(0), 0.0, NewtonSettings())  # type: ignore[arg-type]
    assert result.residual == 0.0 and result.converged is False and result.iterations == 0


def test_backtracking_takes_the_first_halving_that_lowers_the_scaled_residual() -> None:
    damped = NewtonSettings(damped=True, max_iterations=1)
    # tanh(q) - 0.5 from 0: the full step (0.5) lowers |f| from 0.5 to 0.038 and is taken as it is
    # (twice it would lower |f| too); rows scaled by 10, judged scaled.
    saturating = OneUnknown(lambda q: math.tanh(q) - 0.5, lambda q: 1.0 - math.tanh(q) ** 2, row_scale=10.0)
    assert newton(saturating, np.array([0.0]), 0.0, damped).q[0] == 0.5  # type: ignore[arg-type]
    # exp(q) - 1 from -3: the full step (e^3 - 1 = 19.09) and its halves to a quarter raise |f|;
    # an eighth of it (to -0.614) lowers it from 0.950 to 0.459.
    steep = OneUnknown(lambda q: math.exp(q) - 1.0, math.exp)
    full = math.exp(3.0) - 1.0
    assert newton(steep, np.array([-3.0]), 0.0, damped).q[0] == pytest.approx(-3.0 + full / 8, rel=1e-14)  # type: ignore[arg-type]


def test_the_step_tolerance_stops_at_the_round_off_of_large_coordinates() -> None:
    """A gear after thousands of turns (planetary_gears, 9067 turns: angles of 6e4 rad): a step of
    1e-12 is below 4 ulps of such a coordinate (5.8e-11), so only an exact 0 met it and every Newton
    call failed; the time loop then crawled in halved steps for hours. Newton now stops at the
    coordinate's round-off, and at the default's scale (below 1e3) the tolerance is unchanged."""
    scenario = scenarios.build("planetary_gears", overrides={"revolutions": 9067.0, "steps": 12})
    system = ConstraintSystem(scenario)
    t = 0.5 * scenario.t_end
    truth = exact(scenario, np.array([t]))
    assert truth.position is not None
    q = np.zeros(system.layout.size)
    for k, body in enumerate(truth.bodies):
        column = system.layout.body_column(body)
        assert column is not None
        q[column : column + 3] = truth.position[0, k]
    assert np.max(np.abs(q / system.column_scales)) > 1e4
    perturbed = q + 1e-9 * system.column_scales
    result = newton(system, perturbed, t, NewtonSettings())
    assert result.converged and result.iterations <= 3
    np.testing.assert_allclose(result.q, q, rtol=1e-14, atol=1e-9)
    assert newton_round_off(np.array([1e3])) < 1e-12 < newton_round_off(np.array([1.2e3]))
