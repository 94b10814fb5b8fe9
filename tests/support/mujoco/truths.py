"""The native truth of dynamic scenarios for MuJoCo's dynamics tests, computed once per test process."""

from __future__ import annotations

from functools import cache

import numpy as np

import scenarios
from adapters.base import Setting
from adapters.mujoco import MujocoAdapter
from reference_solver.dynamics import simulate
from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory
from tests.support.truths import compiled

ADAPTER = MujocoAdapter()


@cache
def truth(name: str, **overrides: float) -> tuple[Scenario, Trajectory]:
    """The scenario and its native truth: rtol 1e-13 over the full horizon, 1e-11 over a shortened
    one (the default suite's; still below every MuJoCo error it is held against)."""
    scenario = scenarios.build(name, overrides=overrides) if overrides else scenarios.load(name)
    rtol = 1e-11 if overrides else 1e-13
    return scenario, simulate(scenario, scenario.times(), rtol=rtol, compiled=compiled(scenario)).trajectory()


def errors(name: str, setting: Setting | None = None, **overrides: float) -> dict[str, float]:
    """Maximum absolute error per level of `setting` (the default) against the native truth."""
    scenario, expected = truth(name, **overrides)
    result = ADAPTER.run(scenario, setting)
    assert result.status == "ok", result.message
    got = result.trajectory
    assert got is not None
    expected = expected.select(got.bodies)
    found: dict[str, float] = {}
    for level in got.levels:
        ours, theirs = got.level(level), expected.level(level)
        assert ours is not None and theirs is not None
        found[level] = float(np.abs(ours - theirs).max())
    return found
