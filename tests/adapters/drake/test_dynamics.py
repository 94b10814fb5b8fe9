"""The Drake adapter on the dynamics suite's scenes against the native forward dynamics (the
suite's truth, DOP853 at tight tolerance, independent of Drake), and what it refuses there.

SAP's step is first order in free dynamics (q(n+1) = q(n) + h v(n+1), v(n+1) implicit): the errors
fall tenfold with the step. Bounds are the measured maxima at the default setting (1/1000 of the
shortest period) with a margin of about 2."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

pytest.importorskip("pydrake", reason="Drake is not installed (pip install -e '.[drake]')")

import scenarios
from adapters.drake import DrakeAdapter
from reports.dynamics.cases import truth
from scenarios.forces import SpringDamper
from scenarios.scenario import Level, Scenario

LEVELS: tuple[Level, ...] = ("position", "velocity", "acceleration")
BOUNDS = {  # largest absolute error per level at the default setting
    "compound_pendulum/small_oscillation": (4e-7, 2e-6, 1.1e-5),
    "four_bar_gravity": (9e-2, 2.5, 230.0),
    "slider_crank_spring": (4.5e-3, 0.18, 6.7),
    "andrews_squeezer": (1.4e-2, 5.3, 8e3),
}


def errors(scenario: Scenario, **options: object) -> dict[str, float]:
    adapter = DrakeAdapter()
    setting = adapter.default_setting(scenario).replace(**options)  # type: ignore[arg-type]
    result = adapter.run(scenario, setting)
    assert result.status == "ok", result.message
    assert result.trajectory is not None
    times = result.trajectory.times
    native = truth(scenario, times).trajectory.select(result.trajectory.bodies)
    found: dict[str, float] = {}
    for level in LEVELS:
        ours, theirs = result.trajectory.level(level), native.level(level)
        assert ours is not None and theirs is not None
        found[level] = float(np.max(np.abs(ours - theirs)))
    return found


@pytest.mark.parametrize("name", sorted(BOUNDS))
def test_default_follows_the_native_dynamics(name: str) -> None:
    found = errors(scenarios.build(name))
    assert all(found[lv] < bound for lv, bound in zip(LEVELS, BOUNDS[name], strict=True)), found


def test_free_dynamics_is_first_order_in_the_step() -> None:
    """A tenth of the step, a tenth of the error (measured 1.81e-7 -> 1.92e-8 in position)."""
    scenario = scenarios.build("compound_pendulum/small_oscillation")
    dt = float(DrakeAdapter().default_setting(scenario).get("dt"))
    coarse, fine = errors(scenario), errors(scenario, dt=dt / 10)
    for level in LEVELS:
        assert 6 < coarse[level] / fine[level] < 15, (level, coarse, fine)


def test_the_first_output_is_the_start() -> None:
    """The first output is the scenario's start and the acceleration of Drake's first step, not the
    state after it (Drake's Simulator takes the step at t = 0 when it is advanced to 0)."""
    scenario = scenarios.build("compound_pendulum")
    adapter = DrakeAdapter()
    result = adapter.run(scenario, adapter.default_setting(scenario))
    assert result.trajectory is not None and result.trajectory.position is not None
    native = truth(scenario, result.trajectory.times[:2]).trajectory.select(result.trajectory.bodies)
    assert native.position is not None
    assert np.max(np.abs(result.trajectory.position[0] - native.position[0])) < 1e-12


def test_the_ladder_of_free_dynamics_is_the_step_alone() -> None:
    scenario = scenarios.build("four_bar_gravity")
    ladder = DrakeAdapter().ladder(scenario)
    steps = [float(s.get("dt")) for s in ladder]
    assert steps == sorted(steps, reverse=True) and len(set(steps)) == len(steps)


def test_a_spring_of_zero_free_length_is_unsupported_with_the_reason() -> None:
    scenario = scenarios.build("slider_crank_spring")
    forces = tuple(replace(f, free_length=0.0) if isinstance(f, SpringDamper) else f for f in scenario.forces)
    reason = DrakeAdapter().supports(replace(scenario, forces=forces))
    assert reason is not None and "positive free length" in reason


def test_free_dynamics_carries_the_tree_joints_reactions() -> None:
    """Reactions of the tree's joints (the plant's reaction-forces output); the loop-closing joint
    (a ball constraint) has none in Drake, and a free scene has no driver."""
    scenario = scenarios.build("four_bar_gravity")
    adapter = DrakeAdapter()
    result = adapter.run(scenario, adapter.default_setting(scenario))
    assert result.trajectory is not None
    columns = sorted(result.trajectory.extras)
    assert len(columns) == 6 and all(c.endswith((".fx", ".fy")) for c in columns), columns
