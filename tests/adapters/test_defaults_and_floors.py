"""Each engine's default by the settings rule and the floor of its ladder, held two-sided
(tests.support.bounds: within a factor 3 of the value measured when the rule landed, either way), so
a change in the rule, an adapter or an engine shows. Round-off values are held from above only.

Measured on the 2-core machine with mujoco 4.0.0, exudyn 1.13.6 and pin 4.1.0 against the harness
truth (closed forms, the native forward dynamics), as the runner measures them
(reports.scoring.level_error)."""

from __future__ import annotations

import numpy as np
import pytest

import adapters
import scenarios
from adapters.base import Setting
from reports.scoring.level_error import level_errors
from reports.scoring.truth import independent_truth
from tests.support.bounds import held

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


KINEMATIC_DEFAULTS: dict[tuple[str, str], tuple[float, float, float]] = {
    # RK4 at 1/2000 of the turn, tc 128 steps, the regulariser scaled by 1e-8 (before: tc 4 steps
    # with MuJoCo's own regulariser, A 2.2e-4 / 4.4e-4 / 3.3e-5)
    ("slider_crank", "mujoco"): (1.3e-11, 5.3e-11, 2.1e-10),
    ("four_bar", "mujoco"): (2.4e-11, 1.7e-10, 8.7e-10),
    ("cam_roller", "mujoco"): (2.5e-12, 8.5e-12, 3.0e-11),
    # GA3 at 1/2000 of the turn after its run-in: positions to Newton's tolerance (before the run-in
    # the accelerations carried the start-up transient: 6.1e-3, 5.7e-2, 1.6e-3)
    ("slider_crank", "exudyn"): (1.1e-15, 1.6e-6, 4.8e-6),
    ("four_bar", "exudyn"): (1.3e-15, 8.7e-6, 7.3e-5),
    ("cam_roller", "exudyn"): (1.8e-15, 1.9e-7, 5.3e-7),
}
"""(scenario, engine): its errors per level at the engine's default setting, measured."""
DYNAMIC_DEFAULTS: dict[tuple[str, str], tuple[float, float, float]] = {
    ("four_bar_gravity", "mujoco"): (2.8e-10, 1.5e-9, 1.8e-8),
    ("four_bar_gravity", "exudyn"): (1.6e-5, 8.2e-5, 9.2e-4),
    ("four_bar_gravity", "pinocchio"): (1.3e-9, 6.8e-9, 8.1e-8),
    ("andrews_squeezer", "mujoco"): (1.3e-9, 3.4e-9, 3.0e-8),
    ("andrews_squeezer", "exudyn"): (4.5e-5, 1.1e-4, 1.1e-3),
    ("andrews_squeezer", "pinocchio"): (1.5e-8, 3.8e-8, 3.5e-7),
    # the 9-link pendulum; MuJoCo no more Euler at 5e-3 s above 8 bodies (then 9.9e-2 / 1.3e-1 / 8.7e-1)
    ("compound_pendulum", "mujoco"): (4.0e-12, 2.8e-11, 3.6e-10),
    ("compound_pendulum", "exudyn"): (2.7e-6, 1.8e-5, 1.9e-4),
    ("compound_pendulum", "pinocchio"): (6.3e-11, 4.4e-10, 5.8e-9),
}
"""(scenario, engine): its errors per level at the engine's default in free dynamics, measured
against the native forward dynamics (the compound pendulum with 9 links)."""
OVERRIDES: dict[str, dict[str, float]] = {"compound_pendulum": {"links": 9}}
FLOORS: dict[tuple[str, str], tuple[float, float, float]] = {
    ("slider_crank", "mujoco"): (5.5e-12, 5.5e-12, 2.3e-11),
    ("andrews_squeezer", "pinocchio"): (1.3e-12, 2.3e-12, 2.0e-11),
    ("slider_crank", "exudyn"): (1.8e-15, 1.6e-8, 5.0e-6),
}
"""(scenario, engine): the errors at the floor of the engine's ladder (each test below says which
setting that is), measured."""


@pytest.mark.parametrize(("name", "engine"), list(KINEMATIC_DEFAULTS))
def test_kinematic_default(name: str, engine: str) -> None:
    held(errors(name, engine), KINEMATIC_DEFAULTS[(name, engine)])


@pytest.mark.slow
@pytest.mark.parametrize(("name", "engine"), list(DYNAMIC_DEFAULTS))
def test_dynamic_default(name: str, engine: str) -> None:
    held(errors(name, engine, **OVERRIDES.get(name, {})), DYNAMIC_DEFAULTS[(name, engine)])


def test_mujoco_s_floor_on_the_slider_crank() -> None:
    """The ladder's longest time constant (256 steps at the default step, the regulariser scaled,
    adapters.mujoco.weights): RK4's error on the constraint mode, (dt / tc)^4,
    ten times below the default's."""
    adapter = adapters.load("mujoco")
    default = adapter.default_setting(scenarios.load("slider_crank"))
    floor = default.replace(tc=256 * float(default["dt"]))
    assert floor in adapter.ladder(scenarios.load("slider_crank"))
    held(errors("slider_crank", "mujoco", floor), FLOORS[("slider_crank", "mujoco")])


@pytest.mark.slow
def test_pinocchio_s_floor_on_andrews_squeezer() -> None:
    """The ladder's finest RK4 without gains (10000 steps per period): the native truth's level."""
    adapter = adapters.load("pinocchio")
    scenario = scenarios.load("andrews_squeezer")
    finest = adapter.free_setting(scenario, "dynamic", 10000)
    assert finest in adapter.ladder(scenario)
    held(errors("andrews_squeezer", "pinocchio", finest), FLOORS[("andrews_squeezer", "pinocchio")])


@pytest.mark.slow
def test_exudyn_s_floor_on_the_slider_crank() -> None:
    """GA3 at the ladder's finest step (20000 per turn): velocities O(h^2) a hundred times below the
    default's; the accelerations at the default's, where Newton's round-off over h^2 sets them."""
    adapter = adapters.load("exudyn")
    scenario = scenarios.load("slider_crank")
    finest = adapter.ladder(scenario)[4]
    assert finest.mode == "GA3"
    held(errors("slider_crank", "exudyn", finest), FLOORS[("slider_crank", "exudyn")])
