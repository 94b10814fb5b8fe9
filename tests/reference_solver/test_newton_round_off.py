"""Newton's step tolerance floor (newton._step_tolerance, _round_off): ROUND_OFF_ULPS units of
round-off of the largest scaled coordinate. The gear test of test_newton.py converges with an exact
zero step (its rows are linear in the angles), so it passes without the floor; here a root that no
float hits makes Newton step by one ulp for ever unless the floor accepts it."""

from __future__ import annotations

import math

import numpy as np

from reference_solver.limits import ROUND_OFF_ULPS
from reference_solver.newton import NewtonSettings, _round_off, _step_tolerance, newton
from tests.support.newton_systems import OneUnknown

EPS = float(np.finfo(float).eps)


def test_a_root_between_two_floats_of_a_large_coordinate_converges_within_an_ulp() -> None:
    """q^2 = 3600000001 (q = 60000.0000083...), scaled residual (q^2 - A) / 1e6 (round-off 5e-13):
    Newton from 60001 reaches the root's floats in three iterations, then steps by one ulp of 6e4
    (7.3e-12, above the 1e-12 tolerance, below the floor 4 eps 6e4 = 5.3e-11) from one side to the
    other. Measured: converged at iteration 3; without the floor, not in 25."""
    a = 3600000001.0
    square = OneUnknown(lambda q: (q * q - a) / 1e6, lambda q: 2.0 * q / 1e6)
    result = newton(square, np.array([60001.0]), 0.0, NewtonSettings())  # type: ignore[arg-type]
    assert result.converged and result.iterations == 3
    assert abs(result.q[0] - math.sqrt(a)) <= math.ulp(60000.0)


def test_the_floor_is_round_off_units_of_the_largest_scaled_coordinate() -> None:
    assert ROUND_OFF_ULPS == 4
    assert _round_off(np.array([0.005])) == 4 * EPS * 0.005
    assert _round_off(np.array([-3.0, 2.0])) == 4 * EPS * 3.0
    assert _round_off(np.zeros(0)) == 0.0
    large = np.array([6e4])
    assert _step_tolerance(NewtonSettings(step_tolerance=1e-12), large) == 4 * EPS * 6e4
    assert _step_tolerance(NewtonSettings(step_tolerance=1e-12), np.array([0.5])) == 1e-12
    assert _step_tolerance(NewtonSettings(step_tolerance=0.0), large) == 0.0  # 0 stays 0: strict
