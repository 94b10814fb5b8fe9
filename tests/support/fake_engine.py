"""A fake engine and a fake truth for the runner's tests (a fake is fine for testing the runner;
the engines themselves are tested with their real libraries elsewhere).

The truth is an analytic motion of every output body. The fake's `good` mode returns it with a
known error: x of the first body off by `dt` (so the position length error is exactly dt), the
velocities exact, no accelerations. The other modes crash, hang, diverge, return NaN or raise.
"""

from __future__ import annotations

import ctypes
import os
import signal
import time
from pathlib import Path

import numpy as np

from adapters.base import Adapter, Diverged, Option, Setting
from scenarios import Scenario, Trajectory

GOOD = (Setting.of("good", dt=0.01), Setting.of("good", dt=0.001))
BAD = tuple(Setting.of(mode) for mode in ("crash", "hang", "diverge", "nan", "raise"))


def fake_truth(scenario: Scenario, times: np.ndarray) -> Trajectory:
    t = np.asarray(times, dtype=float)[:, None]
    bodies = scenario.output_bodies
    k = np.arange(1, len(bodies) + 1)[None, :]
    position = np.stack([0.01 * k * np.cos(t), 0.02 * k * t, k * t], axis=-1)
    velocity = np.stack([-0.01 * k * np.sin(t), 0.02 * k + 0 * t, k + 0 * t], axis=-1)
    acceleration = np.stack([-0.01 * k * np.cos(t), 0 * k * t, 0 * k * t], axis=-1)
    return Trajectory(t[:, 0], bodies, position, velocity, acceleration)


class FakeAdapter(Adapter):
    """Writes one line to `log` per simulate call, so tests can count runs made in child processes."""

    name = "fake"
    modes = ("good", "crash", "hang", "diverge", "nan", "raise")
    options = (Option("dt", float, 0.0, 1.0, low_open=True),)

    def __init__(self, log: Path) -> None:
        super().__init__()
        self.log = log

    def version(self) -> str:
        return "0.0-fake"

    def default_setting(self, scenario: Scenario) -> Setting:
        return GOOD[1]

    def ladder(self, scenario: Scenario) -> list[Setting]:
        return [*GOOD, *BAD]

    def build(self, scenario: Scenario, setting: Setting) -> tuple[Scenario, Setting]:
        return scenario, setting

    def simulate(self, model: tuple[Scenario, Setting], times: np.ndarray) -> Trajectory:
        scenario, setting = model
        with self.log.open("a") as log:
            log.write(f"{scenario.name} {setting.label}\n")
        self.count_steps(len(times) - 1)
        truth = fake_truth(scenario, times)
        if setting.mode == "crash":
            ctypes.string_at(0)  # a real segmentation fault
        if setting.mode == "hang":
            time.sleep(3600)
        if setting.mode == "diverge":
            raise Diverged("state exploded", time=float(times[3]))
        if setting.mode == "raise":
            raise RuntimeError("engine internal error")
        position = truth.position.copy()
        if setting.mode == "nan":
            position[5:, 0, 0] = np.nan
        else:
            position[:, 0, 0] += setting["dt"]
        return Trajectory(truth.times, truth.bodies, position, truth.velocity)


class WorkerKiller(FakeAdapter):
    """The fake at its default setting, except that on the four_bar family it kills the Dask worker
    process that runs it (once: it leaves `log`.killed behind, and is a plain fake after that)."""

    name = "killer"

    def ladder(self, scenario: Scenario) -> list[Setting]:
        return [GOOD[1]]

    def simulate(self, model: tuple[Scenario, Setting], times: np.ndarray) -> Trajectory:
        scenario, _ = model
        flag = self.log.with_suffix(".killed")
        if scenario.family == "four_bar" and not flag.exists():
            from distributed import get_worker

            get_worker()  # ValueError outside a Dask worker: never kill anything else
            flag.touch()
            os.kill(os.getppid(), signal.SIGKILL)  # this run is a forked child of the worker process
            time.sleep(60)
        return super().simulate(model, times)


def fake_loader(log: Path):  # type: ignore[no-untyped-def]
    """A loader that knows the fake and an engine that is not installed."""
    import adapters

    def load(name: str) -> Adapter:
        if name == "fake":
            return FakeAdapter(log)
        if name == "killer":
            return WorkerKiller(log)
        if name == "absent":
            raise adapters.EngineUnavailable("engine 'absent' is not installed")
        return adapters.load(name)

    return load
