"""MuJoCo's work-precision ladder: RK4 and implicitfast over rungs of steps per period, the time
constant, the regulariser, the solref form and the impedance beside them, and MuJoCo untuned
(adapters.mujoco.settings).

With the constraint time constant tied to the step (the default's 128 steps, the regulariser
scaled), RK4 is far more accurate than implicitfast at the same step.
"""

from __future__ import annotations

import numpy as np
import pytest

import scenarios
from adapters.mujoco import MujocoAdapter
from adapters.mujoco.settings import IMPEDANCE, INVWEIGHT, TC_STEPS, UNTUNED
from scenarios.closed_form import exact

ADAPTER = MujocoAdapter()


def _ladder_errors(name: str, mode: str, column: slice = slice(0, 2)) -> tuple[np.ndarray, np.ndarray]:
    """Engine steps and maximum position errors (lengths by default) of the ladder's settings in
    `mode`."""
    scenario = scenarios.build(name)
    steps, errors = [], []
    for setting in ADAPTER.ladder(scenario):
        if setting.mode != mode or setting["tc"] != pytest.approx(TC_STEPS * setting["dt"]):
            continue
        if setting["impedance"] != IMPEDANCE or setting["invweight"] != INVWEIGHT or setting.get("solref"):
            continue
        result = ADAPTER.run(scenario, setting)
        assert result.status == "ok", result.message
        trajectory = result.trajectory
        assert trajectory is not None and trajectory.position is not None
        truth = exact(scenario, trajectory.times).select(trajectory.bodies)
        assert truth.position is not None
        steps.append(float(setting["dt"]))
        errors.append(np.abs(trajectory.position - truth.position)[..., column].max())
    return np.array(steps), np.array(errors)


def test_ladder_is_rk4_and_implicitfast_over_steps_time_constants_and_impedance() -> None:
    ladder = ADAPTER.ladder(scenarios.build("four_bar"))
    assert {s.mode for s in ladder} == {"RK4", UNTUNED, "implicitfast"}
    tuned = [s for s in ladder if s.mode != UNTUNED]
    assert len({s["dt"] for s in tuned if s.mode == "RK4"}) >= 5
    scaled = {round(s["tc"] / s["dt"]) for s in tuned if s["invweight"] == INVWEIGHT}
    assert scaled == {16, 64, 128, 256, 10000}
    others = {
        (s["invweight"], round(s["tc"] / s["dt"])) for s in tuned if s["invweight"] not in (INVWEIGHT, 1.0)
    }
    assert others == {(1e-6, 128), (1e-4, 32)}
    assert {round(s["tc"] / s["dt"]) for s in tuned if s["invweight"] == 1.0} == {2, 4, 16}
    assert {s["impedance"] for s in tuned} == {0.99, 0.9999}


def test_implicitfast_s_position_error_converges_at_second_order() -> None:
    """Its time constant tied to the step (measured orders 1.6 to 2.0)."""
    steps, errors = _ladder_errors("slider_crank", "implicitfast")
    orders = np.diff(np.log(errors)) / np.diff(np.log(steps))
    assert np.all((orders > 1.4) & (orders < 2.2)), orders


def test_rk4_s_position_error_falls_at_fourth_order_to_its_floor() -> None:
    """RK4's own order from the coarsest rung (measured 5.3), then the floor of the scaled
    regulariser and round-off (1e-11)."""
    steps, errors = _ladder_errors("slider_crank", "RK4")
    orders = np.diff(np.log(errors)) / np.diff(np.log(steps))
    assert orders[0] > 3.5 and errors[1:].max() < 1e-10, (orders, errors)


def test_rk4_is_far_more_accurate_than_implicitfast_at_the_same_step() -> None:
    rk4_steps, rk4 = _ladder_errors("four_bar", "RK4")
    implicit_steps, implicit = _ladder_errors("four_bar", "implicitfast")
    same = np.isin(rk4_steps, implicit_steps)
    assert same.sum() >= 4
    assert np.all(implicit[np.isin(implicit_steps, rk4_steps)] > 100.0 * rk4[same])


def test_gears_stay_at_round_off_across_the_rk4_ladder() -> None:
    _, angles = _ladder_errors("spur_gears", "RK4", slice(2, 3))
    assert 0.0 < angles.max() < 5e-11
