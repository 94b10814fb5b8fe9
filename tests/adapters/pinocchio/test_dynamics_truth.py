"""Pinocchio in free dynamics against the native truth (the native forward dynamics at rtol 1e-13,
an independent formulation in absolute coordinates). The truth takes 10 to 40 s a scenario here, so
these tests are slow; test_dynamics_free.py keeps the fast checks.

Measured largest errors of the default setting (Baumgarte RK4, 8 steps per output interval; 4 on
stiff_spring's 1000 intervals) over the whole scenario, position (m or rad) / velocity:
    four_bar_gravity               5.0e-06 / 1.1e-04
    andrews_squeezer               7.0e-05 / 3.9e-02
    compound_pendulum              1.1e-09 / 8.7e-09
    slider_crank_spring            3.0e-08 / 1.3e-05
    slider_crank_spring/undamped   7.7e-05 / 1.1e-02
    stiff_spring                   1.1e-12 / 1.5e-10
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

pytestmark = pytest.mark.slow

BOUNDS = {
    "four_bar_gravity": (1.5e-5, 3.5e-4),
    "andrews_squeezer": (2e-4, 0.12),
    "compound_pendulum": (3e-9, 3e-8),
    "slider_crank_spring": (1e-7, 4e-5),
    "slider_crank_spring/undamped": (2.5e-4, 3.5e-2),
    "stiff_spring": (3.5e-12, 5e-10),
}


@functools.cache
def truth(name: str) -> Trajectory:
    scenario = scenarios.load(name)
    return simulate(scenario, scenario.times(), rtol=1e-13).trajectory()


def largest(found: Trajectory, expected: Trajectory, level: str) -> float:
    return float(np.max(np.abs(np.asarray(found.level(level)) - np.asarray(expected.level(level)))))  # type: ignore[arg-type]


@pytest.mark.parametrize("name", list(BOUNDS))
def test_default_setting_against_the_native_truth(name: str) -> None:
    scenario = scenarios.load(name)
    result = PinocchioAdapter().run(scenario)
    assert result.status == "ok", result.message
    assert result.trajectory is not None
    expected = truth(name)
    errors = [largest(result.trajectory, expected, level) for level in ("position", "velocity")]
    assert all(e < b for e, b in zip(errors, BOUNDS[name], strict=True)), errors


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
