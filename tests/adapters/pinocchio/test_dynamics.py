"""The Pinocchio adapter's dynamic modes: constraintDynamics with RK4 against the closed forms.

Measured maxima over one revolution at 1000 RK4 steps per revolution (kp = kd = 0), against which
the bounds are set with a margin of about three:
    slider_crank               position 3.4e-11  velocity 8.0e-10  acceleration 2.4e-08
    four_bar                   position 5.6e-10  velocity 4.1e-08  acceleration 6.7e-06
    slider_crank/slider_drive  position 2.9e-09  velocity 1.4e-07  acceleration 3.7e-05
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import scenarios
from adapters.pinocchio import PinocchioAdapter
from scenarios.closed_form import exact

LEVELS = ("position", "velocity", "acceleration")
BOUNDS = {
    "slider_crank": (1e-10, 3e-9, 1e-7),
    "four_bar": (2e-9, 1.5e-7, 2e-5),
    "slider_crank/slider_drive": (1e-8, 5e-7, 1.2e-4),
}


def errors(name: str, steps_per_period: int, mode: str = "dynamic") -> tuple[list[float], int]:
    adapter = PinocchioAdapter()
    scenario = scenarios.build(name)
    result = adapter.run(scenario, adapter.dynamic_setting(scenario, steps_per_period, mode))
    assert result.status == "ok", result.message
    trajectory = result.trajectory
    assert trajectory is not None
    truth = exact(scenario, trajectory.times)
    found = [float(np.max(np.abs(trajectory.level(lv) - truth.level(lv)))) for lv in LEVELS]
    return found, result.steps


@pytest.mark.parametrize("name", list(BOUNDS))
def test_rk4_at_1000_steps_per_revolution(name: str) -> None:
    found, steps = errors(name, 1000)
    assert steps == 1000  # 200 output intervals of 5 RK4 steps
    assert all(e < b for e, b in zip(found, BOUNDS[name], strict=True)), found


def test_rk4_converges_at_fourth_order() -> None:
    """Three times fewer steps cost close to 3^4 = 81 in position error."""
    coarse, _ = errors("slider_crank", 300)
    fine, _ = errors("slider_crank", 1000)
    assert coarse[0] / fine[0] > 25


def test_baumgarte_gains_reduce_drift_of_the_slider_drive() -> None:
    """Gains kp = w^2, kd = 2 w feed the drive and loop drift back: measured 1.0e-10 against
    2.9e-9 without them at 1000 steps per revolution."""
    plain, _ = errors("slider_crank/slider_drive", 1000)
    damped, _ = errors("slider_crank/slider_drive", 1000, "baumgarte")
    assert damped[0] < plain[0] / 5


def test_ladder_has_the_three_curves_where_dynamics_is_supported() -> None:
    adapter = PinocchioAdapter()
    modes = [s.mode for s in adapter.ladder(scenarios.build("four_bar"))]
    assert sorted(set(modes)) == ["baumgarte", "dynamic", "kinematic"]
    # the cams' dynamic modes run (test_cam_dynamics.py) but cost 5-15 ms a step: not swept
    assert {s.mode for s in adapter.ladder(scenarios.build("cam_roller"))} == {"kinematic"}


def test_driven_motion_does_not_depend_on_the_masses() -> None:
    """Fully driven, the constrained acceleration is kinematic: other masses and inertias change
    only the constraint forces (measured differences 8e-15, 7e-13, 1.3e-10 against 2e-8 of RK4
    truncation at 300 steps per revolution)."""
    adapter = PinocchioAdapter()
    light = scenarios.build("four_bar")
    heavy = dataclasses.replace(
        light,
        bodies=tuple(
            dataclasses.replace(b, mass=b.mass * (7 + 3 * k), inertia=b.inertia * (0.2 + 5 * k))
            for k, b in enumerate(light.bodies)
        ),
    )
    setting = adapter.dynamic_setting(light, 300)
    runs = [adapter.run(s, setting).trajectory for s in (light, heavy)]
    assert runs[0] is not None and runs[1] is not None
    differences = [float(np.max(np.abs(runs[0].level(lv) - runs[1].level(lv)))) for lv in LEVELS]
    assert all(d < b for d, b in zip(differences, (1e-13, 1e-11, 2e-9), strict=True)), differences
