"""A coordinate that is NaN at a time leaves the constraints it enters unevaluable: the residual there
is NaN on both the compiled and the plain rows, never the largest of the rows that could be read (a
NaN skipped by max() would read as a closed loop), and every other time keeps its value."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import scenarios
from reference_solver import analyse
from reference_solver.residual import constraint_residual, plain_constraint_residual

CASES = ["four_bar", "slider_crank", "cam_roller", "cam_flat_face/spline"]


@pytest.mark.parametrize("name", CASES)
@pytest.mark.parametrize("level", [0, 2])  # x and theta of a body
def test_a_nan_coordinate_gives_a_nan_residual_at_its_time_only(name: str, level: int) -> None:
    scenario = scenarios.load(name, {"steps": "20"})
    solution = analyse(scenario).trajectory()
    assert solution.position is not None
    position = solution.position.copy()
    moving = next(i for i, b in enumerate(solution.bodies) if b != "ground")
    position[7, moving, level] = np.nan
    broken = dataclasses.replace(solution, position=position)
    for measure in (constraint_residual, plain_constraint_residual):
        clean, found = measure(scenario, solution), measure(scenario, broken)
        assert np.isnan(found[7]), measure.__name__
        others = np.arange(len(found)) != 7
        assert np.all(np.isfinite(found[others]))
        np.testing.assert_array_equal(found[others], clean[others])
