"""MuJoCo's work-precision sweep: RK4 and implicitfast at three step sizes.

With the constraint time constant tied to the step (solref 2 dt), both integrators converge in
position at second order in dt on the slider-crank (measured RK4 2.5e-6 / 5.0e-8 / 6.1e-10 and
implicitfast 1.1e-3 / 2.3e-5 / 2.9e-7 m at engine steps 6.3e-4 / 9.0e-5 / 1.0e-5 s), RK4 about
500 times more accurate at the same step.
"""

from __future__ import annotations

import numpy as np
import pytest

import scenarios
from adapters.mujoco import MujocoAdapter
from adapters.mujoco.stepping import engine_step
from scenarios.closed_form import exact

ADAPTER = MujocoAdapter()


def _sweep_errors(name: str, mode: str, column: slice = slice(0, 2)) -> tuple[np.ndarray, np.ndarray]:
    """Engine steps and maximum position errors (lengths by default) of the sweep's settings in
    `mode`."""
    scenario = scenarios.build(name)
    interval = scenario.t_end / scenario.steps
    steps, errors = [], []
    for setting in ADAPTER.sweep(scenario):
        if setting.mode != mode:
            continue
        result = ADAPTER.run(scenario, setting)
        assert result.status == "ok", result.message
        trajectory = result.trajectory
        assert trajectory is not None and trajectory.position is not None
        truth = exact(scenario, trajectory.times).select(trajectory.bodies)
        assert truth.position is not None
        steps.append(engine_step(float(setting["dt"]), interval))
        errors.append(np.abs(trajectory.position - truth.position)[..., column].max())
    return np.array(steps), np.array(errors)


def test_sweep_is_rk4_and_implicitfast_at_three_steps() -> None:
    sweep = ADAPTER.sweep(scenarios.build("four_bar"))
    assert sorted({s.mode for s in sweep}) == ["RK4", "implicitfast"]
    assert len({s["dt"] for s in sweep}) == 3 and len(sweep) == 6


@pytest.mark.parametrize("mode", ["RK4", "implicitfast"])
def test_position_error_converges_at_second_order(mode: str) -> None:
    steps, errors = _sweep_errors("slider_crank", mode)
    orders = np.diff(np.log(errors)) / np.diff(np.log(steps))
    assert np.all((orders > 1.8) & (orders < 2.2)), orders


def test_rk4_is_far_more_accurate_than_implicitfast_at_the_same_step() -> None:
    _, rk4 = _sweep_errors("four_bar", "RK4")
    _, implicit = _sweep_errors("four_bar", "implicitfast")
    assert np.all(implicit > 100.0 * rk4)


def test_gears_stay_at_round_off_across_the_rk4_sweep() -> None:
    _, angles = _sweep_errors("spur_gears", "RK4", slice(2, 3))
    assert 0.0 < angles.max() < 5e-11
