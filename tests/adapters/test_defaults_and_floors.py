"""Each engine's default by the settings rule and the floor of its ladder, held two-sided
(tests.support.bounds: within a factor 3 of the value measured when the rule landed, either way), so
a change in the rule, an adapter or an engine shows. Round-off values are held from above only.

Measured on the 2-core machine with mujoco 4.0.0, exudyn 1.13.6 and pin 4.1.0 against the harness
truth (closed forms, the native forward dynamics), as the runner measures them
(reports.scoring.level_error)."""

from __future__ import annotations

import pytest

import adapters
import scenarios
from tests.support.bounds import held
from tests.support.default_errors import errors
from tests.support.measured import DYNAMIC_DEFAULTS, FLOORS, KINEMATIC_DEFAULTS

OVERRIDES: dict[str, dict[str, float]] = {"compound_pendulum": {"links": 9}}


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
def test_mujoco_s_floor_on_the_free_four_bar() -> None:
    """The direct solref form at 1e4 steps (next to no stiffness and damping, the loop held by its
    exact accelerations), the regulariser scaled: below the default's 1024 steps in free dynamics."""
    adapter = adapters.load("mujoco")
    scenario = scenarios.load("four_bar_gravity")
    default = adapter.default_setting(scenario)
    floor = default.replace(tc=1e4 * float(default["dt"]), solref="direct")
    assert floor in adapter.ladder(scenario)
    held(errors("four_bar_gravity", "mujoco", floor), FLOORS[("four_bar_gravity", "mujoco")])


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
