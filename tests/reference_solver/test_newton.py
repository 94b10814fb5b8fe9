"""Newton's exits where the mutation run (docs/mutation.md) found them unchecked: a start whose
residual is not finite stops at once, unconverged, with the start unchanged and no factors."""

from __future__ import annotations

import math

import numpy as np

import scenarios
from reference_solver import ConstraintSystem
from reference_solver.newton import NewtonSettings, newton


def test_a_non_finite_start_is_returned_unconverged_at_once() -> None:
    system = ConstraintSystem(scenarios.build("slider_crank"))
    start = np.full(system.unknowns, np.nan)
    result = newton(system, start, 0.0, NewtonSettings())
    assert result.converged is False and result.iterations == 0 and result.factors is None
    assert math.isnan(result.residual)
    assert result.q.shape == start.shape and np.isnan(result.q).all()
