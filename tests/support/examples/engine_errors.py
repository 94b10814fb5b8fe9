"""An example file run on one engine at its default setting, and its dimensionless error per level
against the example's closed form (scaled as reports.scoring.level_error scales a run's)."""

from __future__ import annotations

import numpy as np

import adapters
from adapters.base import RunResult
from reports.scoring.level_error import LEVEL_COLUMNS, level_errors
from scenarios import Scenario, Trajectory
from tests.support.examples.closed_forms import CLOSED_FORMS


def closed_form_trajectory(name: str, scenario: Scenario) -> Trajectory:
    """The example's closed form as a trajectory of its output bodies."""
    times = np.asarray(scenario.times())
    expected = CLOSED_FORMS[name](times)
    bodies = tuple(b for b in scenario.output_bodies if b in expected)
    levels = [np.stack([expected[b][k] for b in bodies], axis=1) for k in range(3)]
    return Trajectory(times, bodies, *levels)


def default_run(engine: str, scenario: Scenario) -> RunResult:
    """The engine's run at its default setting on the scenario's grid."""
    adapter = adapters.load(engine)
    return adapter.run(scenario, adapter.default_setting(scenario), np.asarray(scenario.times()))


def errors(name: str, scenario: Scenario, result: Trajectory) -> dict[str, float]:
    """{level: dimensionless error} against the closed form (NaN for a level not produced)."""
    found = level_errors(scenario, result, closed_form_trajectory(name, scenario))
    return {level: found[column] for level, column in LEVEL_COLUMNS.items()}
