"""Warm workers kept from task to task by a task backend's threads (each task thread of a Dask worker
runs its tasks one after another): the engines' workers (group_runs.Workers, one forked child per
engine) and a worker for the truths, each forked once and used by every later task of the thread,
as the serial runner keeps its workers from group to group. A task that made its own workers forked
a child per group and per truth (a fork of a worker process with every engine and Dask loaded, and
the child's exit, each time).

What a thread keeps is bound to what its tasks were given: the engine loader, the run configuration
and the residual (compared by equality; module-level functions arrive as themselves), and the truth
hook. A task given others (another run on the same cluster, a closure that arrives as a new object)
releases what the thread kept and starts afresh, so nothing runs with another task's settings. A
crash or a timeout costs its own call, and the next call forks a new child (isolation.Worker). A
thread's children die with it (isolation: the parent-death signal); `release_all` releases every
thread's, for a worker that shuts down.
"""

from __future__ import annotations

import functools
import threading
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from adapters.base import Adapter
from reports.run.group_runs import RunConfig, Workers
from reports.run.isolation import Worker
from reports.scoring import Residual
from scenarios import Scenario

TruthWorker = Worker[Scenario, Any]


@dataclass
class _Kept:
    """What one thread keeps: the key its group workers were made for, the adapters loaded under it,
    the workers, and the truth hook with its worker."""

    key: tuple[Any, ...] | None = None
    adapters: dict[str, Adapter] = field(default_factory=dict)
    workers: Workers | None = None
    truth: tuple[Any, TruthWorker] | None = None

    def release_groups(self) -> None:
        if self.workers is not None:
            self.workers.__exit__(None, None, None)
        self.key, self.adapters, self.workers = None, {}, None

    def release_truth(self) -> None:
        if self.truth is not None:
            self.truth[1].close()
        self.truth = None


_local = threading.local()
_every: list[_Kept] = []
_lock = threading.Lock()


def _mine() -> _Kept:
    kept: _Kept | None = getattr(_local, "kept", None)
    if kept is None:
        kept = _local.kept = _Kept()
        with _lock:
            _every.append(kept)
    return kept


def group_workers(
    loader: Callable[[str], Adapter], engine: str, config: RunConfig, residual: Residual | None
) -> tuple[Adapter, Workers]:
    """The engine's adapter, loaded once per thread, and the thread's kept workers for it."""
    kept = _mine()
    key = (loader, config, residual)
    if kept.key is None or kept.key != key:
        kept.release_groups()
        kept.key = key
    adapter = kept.adapters.get(engine)
    if adapter is None:
        adapter = kept.adapters[engine] = loader(engine)  # a loader's error is the task's, not kept
    if kept.workers is None:
        kept.workers = Workers(config, residual)
    return adapter, kept.workers


def truth_worker(truth: Callable[[Scenario, np.ndarray], Any]) -> TruthWorker:
    """The thread's kept worker that solves `truth(scenario, scenario.times())` for each scenario
    sent to it."""
    kept = _mine()
    if kept.truth is None or kept.truth[0] != truth:
        kept.release_truth()
        kept.truth = (truth, Worker(functools.partial(_solve, truth)))
    return kept.truth[1]


def _solve(truth: Callable[[Scenario, np.ndarray], Any], scenario: Scenario) -> Any:
    return truth(scenario, np.asarray(scenario.times()))


def forks() -> int:
    """How many children this thread's kept workers have forked (for the tests and benchmarks)."""
    kept = _mine()
    groups = sum(w.forks for w in kept.workers.workers.values()) if kept.workers is not None else 0
    return groups + (kept.truth[1].forks if kept.truth is not None else 0)


def release_all() -> None:
    """Release every thread's kept workers (a Dask worker that shuts down)."""
    with _lock:
        every = list(_every)
    for kept in every:
        kept.release_groups()
        kept.release_truth()
