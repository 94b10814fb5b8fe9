"""Past a dead point the truth has no configuration, and no forces: the native solver is not asked
for forces it cannot give (its approach to the dead point costs about half a second and fails)."""

from __future__ import annotations

import numpy as np
import pytest

import scenarios
from reference_solver.errors import SolverError
from reports.scoring import truth
from reports.scoring.forces import native_forces
from reports.scoring.truth import closed_form, independent_truth, with_native_forces


def test_a_truth_past_a_dead_point_carries_no_forces_as_the_native_solver_gives_none(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    scenario = scenarios.load("four_bar", {"crank_length": "0.2"})  # a crank too long to turn
    grid = np.asarray(scenario.times())
    exact = closed_form(scenario, grid)
    assert exact is not None and exact.position is not None
    finite = np.isfinite(exact.position).all(axis=(1, 2))
    assert finite[0] and not finite.all()  # a configuration at the start, none from the dead point on
    with pytest.raises(SolverError):  # what the native solver says on this grid
        native_forces(scenario, grid)
    asked: list[float] = []
    monkeypatch.setattr(truth, "native_forces", lambda s, t: asked.append(1) or native_forces(s, t))
    assert with_native_forces(scenario, grid, exact) is exact
    assert not asked  # not asked for what it cannot give
    assert not independent_truth(scenario, grid).trajectory.extras


def test_a_truth_with_a_configuration_everywhere_carries_the_native_forces() -> None:
    scenario = scenarios.load("four_bar", {"steps": "20"})
    grid = np.asarray(scenario.times())
    forces = independent_truth(scenario, grid).trajectory.extras
    assert forces and set(forces) == set(native_forces(scenario, grid))
