"""An engine's errors per level at a setting (its default unless given), against the harness truth, as
the runner measures them (reports.scoring.level_error)."""

from __future__ import annotations

import numpy as np

import adapters
import scenarios
from adapters.base import Setting
from reports.scoring.level_error import level_errors
from reports.scoring.truth import independent_truth

LEVELS = ("error_position", "error_velocity", "error_acceleration")


def errors(name: str, engine: str, setting: Setting | None = None, **overrides: float) -> tuple[float, ...]:
    scenario = scenarios.build(name, overrides=overrides or None)
    adapter = adapters.load(engine)
    setting = setting or adapter.default_setting(scenario)
    result = adapter.run(scenario, setting)
    assert result.status == "ok" and result.trajectory is not None, result.message
    truth = independent_truth(scenario, np.asarray(scenario.times())).trajectory
    found = level_errors(scenario, result.trajectory, truth)
    return tuple(float(found[level]) for level in LEVELS)
