"""Timings shared by the benchmarks: the best of several repeats, and each engine's cost measured
on the same mechanism in the same process."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

import adapters
from adapters.base import Setting
from adapters.timing import fastest
from reference_solver import analyse
from scenarios.scenario import Scenario


def best(action: Callable[[], object], repeats: int = 5, number: int = 1) -> float:
    """The minimum over `repeats` of the time of `number` calls, per call, in seconds, after one
    warm-up call (compilation, caches)."""
    return fastest(action, repeats, warmup=1, number=number)[0]


@dataclass(frozen=True)
class Cost:
    """Microseconds per time point or engine step, or why there is none."""

    value: float | None
    note: str = ""

    def cell(self, width: int = 10) -> str:
        return f"{self.value:{width}.2f}" if self.value is not None else f"{'-':>{width}}"


def native_per_point(scenario: Scenario, compiled: bool, points: int, repeats: int) -> Cost:
    """The native solver's cost per time point at tolerance 1e-12 over a grid of `points` points."""
    grid = np.asarray(scenario.times(steps=points - 1))
    seconds = best(lambda: analyse(scenario, grid, 1e-12, compiled=compiled), repeats)
    return Cost(1e6 * seconds / points)


def mujoco_per_step(scenario: Scenario, mode: str, steps: int, repeats: int) -> tuple[Cost, Cost]:
    """mj_step's cost in `mode` on the adapter's model of the scenario: called from a Python loop,
    and through mj_step's own loop (nstep)."""
    import mujoco

    adapter = adapters.load("mujoco")
    reason = adapter.supports(scenario)
    if reason is not None:
        return Cost(None, reason), Cost(None, reason)
    model = adapter.build(scenario, Setting(mode, adapter.default_setting(scenario).options))
    m, d = model.model, mujoco.MjData(model.model)

    def restart() -> None:
        d.qpos[:], d.qvel[:], d.time = model.qpos0, model.qvel0, 0.0
        mujoco.mj_forward(m, d)

    def python_loop() -> None:
        restart()
        for _ in range(steps):
            mujoco.mj_step(m, d)

    def native_loop() -> None:
        restart()
        mujoco.mj_step(m, d, nstep=steps)

    restart_cost = best(restart, repeats)
    per_call = (best(python_loop, repeats) - restart_cost) / steps
    per_nstep = (best(native_loop, repeats) - restart_cost) / steps
    return Cost(1e6 * per_call), Cost(1e6 * per_nstep)


def exudyn_per_step(scenario: Scenario, repeats: int) -> Cost:
    """Exudyn's cost per step at its default setting: the adapter's whole simulation time (the
    minimum of repeats after a warm-up) over the steps it took."""
    adapter = adapters.load("exudyn")
    result = adapter.run(scenario, repeats=repeats, warmup=1)
    if result.status != "ok" or not result.steps:
        return Cost(None, f"{result.status}: {result.message}")
    return Cost(1e6 * result.run_time / result.steps, result.setting.label)
