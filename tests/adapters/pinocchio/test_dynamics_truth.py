"""Pinocchio in free dynamics against the native truth (the native forward dynamics at rtol 1e-13,
an independent formulation in absolute coordinates). The truth takes 10 to 40 s a scenario here, so
these tests are slow; test_dynamics_free.py keeps the fast checks.

The default setting's largest errors over the whole scenario are in MEASURED (held two-sided);
Pinocchio's default is the settings rule's (docs/settings-rule.md), four_bar_gravity 1.3e-9 m.
n_four_bar is left out: the native truth at rtol 1e-13 stops at t = 2.66 s (its step size
underflows at the singular position).
"""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest

import scenarios
from adapters.pinocchio import PinocchioAdapter
from reference_solver.dynamics import simulate
from scenarios.trajectory import Trajectory
from tests.support.bounds import held
from tests.support.truths import compiled

pytestmark = pytest.mark.slow

MEASURED: dict[str, tuple[float, float, float]] = {
    "four_bar_gravity": (1.3e-09, 3.5e-08, 3.2e-06),
    "andrews_squeezer": (1.5e-08, 8.0e-06, 1.5e-02),
    "compound_pendulum": (2.7e-11, 2.3e-10, 4.8e-09),
    "slider_crank_spring": (2.1e-11, 1.0e-09, 8.8e-08),
    "slider_crank_spring/undamped": (8.8e-06, 8.6e-04, 1.7e00),
    "stiff_spring": (4.3e-13, 1.6e-10, 8.1e-09),
}
"""scenario: the largest position (m or rad), velocity and acceleration errors of the default setting
over the whole scenario, measured, held two-sided (tests.support.bounds)."""


@functools.cache
def truth(name: str) -> Trajectory:
    scenario = scenarios.load(name)
    return simulate(scenario, scenario.times(), rtol=1e-13, compiled=compiled(scenario)).trajectory()


def largest(found: Trajectory, expected: Trajectory, level: str) -> float:
    return float(np.max(np.abs(np.asarray(found.level(level)) - np.asarray(expected.level(level)))))  # type: ignore[arg-type]


@pytest.mark.parametrize("name", list(MEASURED))
def test_default_setting_against_the_native_truth(name: str) -> None:
    scenario = scenarios.load(name)
    result = PinocchioAdapter().run(scenario)
    assert result.status == "ok", result.message
    assert result.trajectory is not None
    expected = truth(name)
    errors = [
        largest(result.trajectory, expected, level) for level in ("position", "velocity", "acceleration")
    ]
    held(errors, MEASURED[name])


def test_rk4_is_fourth_order_against_the_truth_on_four_bar_gravity() -> None:
    """Position error at 50, 100, 200 and 400 steps per shortest period (0.13 s), without Baumgarte:
    ratios near 16."""
    scenario = scenarios.load("four_bar_gravity")
    adapter = PinocchioAdapter()
    steps, errors = [], []
    for n in (50, 100, 200, 400):
        setting = adapter.free_setting(scenario, "dynamic", n)
        result = adapter.run(scenario, setting)
        assert result.status == "ok" and result.trajectory is not None, result.message
        steps.append(1.0 / float(setting["dt"]))  # result.steps adds the side steps to the outputs
        errors.append(largest(result.trajectory, truth("four_bar_gravity"), "position"))
    slope = -np.polyfit(np.log(steps), np.log(errors), 1)[0]
    assert abs(slope - 4.0) < 0.3, (errors, slope)
    assert math.isclose(errors[0] / errors[-1], 8**4, rel_tol=0.25)
