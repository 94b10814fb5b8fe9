"""The independent truth: closed forms wherever a family has one, and the native solver agreeing with
them to 1e-10 at every level (dimensionless) on every family; the refined native solve elsewhere."""

from __future__ import annotations

import numpy as np
import pytest

import reference_solver
import scenarios
from reports.scoring.level_error import level_errors
from reports.scoring.truth import CLOSED_FORM, NATIVE_DYNAMIC, NATIVE_REFINED, independent_truth

FAMILY_DEFAULTS = sorted({scenarios.build(name).family for name in scenarios.catalogue()})


@pytest.mark.parametrize("family", FAMILY_DEFAULTS)
def test_native_solver_meets_the_closed_form_at_every_level(family: str) -> None:
    scenario = scenarios.build(family)
    times = np.asarray(scenario.times())
    truth = independent_truth(scenario, times)
    assert truth.name == CLOSED_FORM
    solved = reference_solver.solve(scenario, times, tolerance=1e-12)
    errors = level_errors(scenario, solved, truth.trajectory, ("position", "velocity", "acceleration"))
    for column, value in errors.items():
        assert value < 1e-10, column


def test_spline_cam_takes_the_refined_native_truth() -> None:
    scenario = scenarios.build("cam_roller/spline")
    times = np.asarray(scenario.times())
    truth = independent_truth(scenario, times)
    assert truth.name == NATIVE_REFINED
    assert truth.trajectory.position is not None and np.isfinite(truth.trajectory.position).all()
    assert np.array_equal(truth.trajectory.times, times)


def test_a_dynamic_scenario_takes_the_tight_native_dynamics() -> None:
    scenario = scenarios.build("compound_pendulum")
    times = np.asarray(scenario.times())[:50]
    truth = independent_truth(scenario, times)
    assert truth.name == NATIVE_DYNAMIC
    assert truth.trajectory.position is not None and np.isfinite(truth.trajectory.position).all()
