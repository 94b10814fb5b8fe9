"""A scenario-engine group's runs: each made in a warm worker (reports.run.isolation.Worker,
forked from this process once it has warmed the scenario, and kept for the engine's next groups),
timed as the minimum of repeats after a warm-up, compared with the truth there, and made into a
row. A crash or a hang costs its own row; the next run gets a new worker. Stores nothing, so that a
group runs the same in the Runner and in a Dask task."""

from __future__ import annotations

import contextlib
import dataclasses
import functools
import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from adapters.base import Adapter, RunResult, Setting
from reports.run.isolation import Outcome, Worker
from reports.run.planning import Group
from reports.run.rows import failure_row, result_row
from reports.run.warm import warm
from reports.scoring import NamedTruth, Residual, measure, step_halving
from scenarios import Scenario
from scenarios.trajectory import Trajectory

LONG_RUN = 0.25  # seconds: a simulation this long is timed once after the warm-up (adapters.base)
REPEATS_BUDGET = 0.25
"""CPU seconds a run's timed repeats may spend (adapters.timing.timed's `budget`): a repeat is made
only where it fits, as long as the best before it, so a run's repeats cost at most the larger of
this and one repeat. Runs under a third of it are timed up to three times, under half of it twice,
longer ones once."""
AGREE = 0.02
"""Repeats stop once one agrees with the best before it to this fraction (adapters.timing.timed):
on a quiet machine two repeats of the same run agree far closer than that (`mbxval bench repeats`
measures it), so a third adds little; on a busy one they disagree and the third runs."""


@dataclass(frozen=True)
class RunConfig:
    """How each engine run is made: the run's configuration (an engine's options are its Setting's).
    `ladder` False runs only each engine's default setting."""

    ladder: bool = True
    repeats: int = 3
    warmup: int = 1
    timeout: float = 60.0
    rerun: bool = False
    keep_failures: bool = False  # keep stored failed/timeout rows instead of retrying them
    keep_stale: bool = False  # keep rows of another revision or engine version, marked stale
    truth_timeout: float = 600.0  # our own solver; its first call may compile its kernels
    save_interval: float = 5.0
    """Seconds between saves while running: a save costs a store generation (about 0.1 s), so rows
    are saved after the group that ends this long after the last save, and always at the end (an
    interrupt or a stop signal saves too); a hard kill loses at most this much work."""


Stored = tuple[dict[str, Any], Trajectory | None]
"""A row and the trajectory kept with it (the default setting's, when ok)."""


def run_group(
    group: Group,
    jobs: list[tuple[Setting, bool]],
    truth: NamedTruth | str,
    config: RunConfig,
    residual: Residual | None,
    done: Callable[[str], None] | None = None,
    workers: Workers | None = None,
) -> list[Stored]:
    """The rows of one scenario-engine group: each job run isolated (a crash or a hang costs its
    row), timed and compared with the truth; `done(label)` after each. The runs are made by the
    engine's warm worker in `workers` (kept for the next group; by default, a worker for this group
    alone). Stores nothing, so that it runs the same here and in a Dask task."""
    timed_out: set[str] = set()
    out: list[Stored] = []
    if not jobs:
        return out
    with contextlib.ExitStack() as stack:
        if workers is None:
            workers = stack.enter_context(Workers(config, residual))
        for setting, is_default in jobs:
            if setting.mode in timed_out:
                message = "not run: a cheaper setting of this mode hit the time limit"
                out.append((failure(group, setting, is_default, "timeout", message), None))
            else:
                outcome = workers.measure(group, truth, setting, is_default)
                out.append(_stored(outcome, group, setting, is_default, truth, config, timed_out))
            if done is not None:
                done(setting.label)
    return out


Measured = tuple[RunResult, int, dict[str, float], tuple[str, ...], str]
"""A run's result, its number of timed repeats, and its comparison (metrics, levels, note)."""
Order = tuple[tuple[Scenario, NamedTruth | str] | None, Setting, bool]
"""What a worker is sent for one run: the group's scenario and truth with the group's first run in
that worker's child (None after: the child holds them), the setting, and whether the run's
trajectory is kept (the default setting's: the others' are not sent back)."""


class Workers:
    """Warm workers for the runs, one per engine adapter, kept from group to group: each forked
    once (and again after a crash or a timeout), not once per group, with the adapter as this
    process holds it. A worker is sent a group's scenario and truth (pickled, about 60 kB) with
    the group's first run in its child. Before a fork this process warms the group's scenario
    (reports.run.warm), so the child inherits the kernels and the scenario's program; a worker
    kept from an earlier group builds a later scenario's program in its untimed warm-up run (warming
    it here would serve no child). Use it as a context manager: leaving it ends the workers."""

    def __init__(self, config: RunConfig, residual: Residual | None) -> None:
        self.config, self.residual = config, residual
        self.workers: dict[int, Worker[Order, Measured]] = {}
        self.held: dict[int, Group] = {}
        """By adapter: the group whose scenario and truth its worker's child holds."""

    def measure(
        self, group: Group, truth: NamedTruth | str, setting: Setting, keep: bool = True
    ) -> Outcome[Measured]:
        """One run of the group at `setting` in the worker of the group's adapter (its trajectory
        sent back when `keep`)."""
        key = id(group.adapter)
        worker = self.workers.get(key)
        if worker is None:
            measure = functools.partial(_measure, group.adapter, self.config, self.residual, {})
            worker = self.workers[key] = Worker(measure)
        if not worker.ready:
            warm(group.scenario)  # before the fork: the child inherits the kernels and the program
        holds = worker.ready and self.held.get(key) is group
        self.held[key] = group
        order: Order = (None if holds else (group.scenario, truth), setting, keep)
        return worker.call(order, self.config.timeout)

    def __enter__(self) -> Workers:
        return self

    def __exit__(self, *exc: Any) -> None:
        for worker in self.workers.values():
            worker.__exit__(*exc)
        self.workers.clear()
        self.held.clear()


def _measure(
    adapter: Adapter | None, config: RunConfig, residual: Residual | None, held: dict[str, Any], order: Order
) -> Measured:
    """One run, timed and compared with the truth (in the worker's child, which keeps the group's
    scenario and truth in `held` for the group's next runs)."""
    sent, setting, keep = order
    if sent is not None:
        held["group"] = sent
    scenario, truth = held["group"]
    assert adapter is not None
    result, repeats = timed_run(adapter, scenario, setting, np.asarray(scenario.times()), config)
    against = truth.trajectory if isinstance(truth, NamedTruth) else truth
    forces = truth.forces if isinstance(truth, NamedTruth) else ""
    compared = measure(scenario, result, against, residual, forces)
    if isinstance(truth, str) and result.trajectory is not None:  # unjudged: its own step halving
        grid = np.asarray(scenario.times())
        compared[0]["step_halving"] = step_halving(adapter, scenario, setting, grid, result.trajectory)
    if not keep:  # a trajectory not kept is not pickled back (tens of kB a run)
        result = dataclasses.replace(result, trajectory=None)
    return (result, repeats, *compared)


def _stored(
    outcome: Outcome[Measured],
    group: Group,
    setting: Setting,
    is_default: bool,
    truth: NamedTruth | str,
    config: RunConfig,
    timed_out: set[str],
) -> Stored:
    """The row of a run (and its trajectory when kept), from what became of it."""
    scenario = group.scenario
    if outcome.kind == "timeout":
        timed_out.add(setting.mode)
        row = failure(group, setting, is_default, "timeout", outcome.message)
        # it spent the limit it hit on the wall clock (its child killed there), at most that in CPU
        row["repeats_time"] = row["repeats_time_wall"] = config.timeout
        return row, None
    if outcome.kind != "ok" or outcome.value is None:
        return failure(group, setting, is_default, "failed", outcome.message), None
    result, repeats, metrics, levels, note = outcome.value
    row = result_row(scenario, result, is_default, repeats, config.warmup, metrics, levels, note)
    row["is_untuned"] = group.is_untuned(setting)
    row["engine"] = group.engine  # the name it was asked by, whatever the adapter calls itself
    row["truth"] = truth.name if isinstance(truth, NamedTruth) else ""
    if not math.isnan(row["error_force"]) and isinstance(truth, NamedTruth):
        row["force_truth"] = truth.forces
    keep = result.trajectory if is_default and result.status == "ok" else None
    return row, keep.select(scenario.output_bodies) if keep is not None else None


def failure(group: Group, setting: Setting, is_default: bool, status: Any, message: str) -> dict[str, Any]:
    """The row of a run of the group that produced nothing to compare."""
    row = failure_row(group.scenario, group.engine, group.version, setting, is_default, status, message)
    row["is_untuned"] = group.is_untuned(setting)
    return row


def timed_run(
    adapter: Adapter, scenario: Scenario, setting: Setting, times: np.ndarray, config: RunConfig
) -> tuple[RunResult, int]:
    """The adapter's run (one build), timed as the minimum of `config.repeats` after
    `config.warmup` untimed warm-up runs over the grid's first interval (Adapter.run), except that a
    run longer than LONG_RUN is timed once (its timing noise is small against its length), the
    repeats stop once two agree to AGREE, and none is made past REPEATS_BUDGET. Returns
    the result and the number of timed repeats it made (1 for a run that failed)."""
    result = adapter.run(
        scenario,
        setting,
        times,
        repeats=config.repeats,
        warmup=config.warmup,
        once_above=LONG_RUN,
        agree=AGREE,
        budget=REPEATS_BUDGET,
    )
    return result, max(1, result.repeats)
