"""Workers kept from task to task by a task thread (a Dask worker's): one fork per engine and one for
the truths serve every task of the thread, the rows and truths are those that workers made afresh for
each task give (to the last bit), and tasks given another configuration, or run in another thread,
do not share them."""

from __future__ import annotations

import math
import threading
from collections.abc import Callable
from typing import Any, TypeVar

import numpy as np
import pytest

import adapters
from reports.run import kept_workers
from reports.run.dask_backend import group_task, truth_task
from reports.run.group_runs import RunConfig, run_group
from reports.run.planning import Group, plan_engine
from reports.run.runner import reference_residual, solve_truth
from reports.scoring.assembly import consistent_start
from reports.scoring.truth import NamedTruth, independent_truth
from scenarios import load as build_scenario
from tests.support.run_columns import VARIES_BETWEEN_RUNS

CONFIG = RunConfig(repeats=1, warmup=0, timeout=60.0)
SCENARIOS = ("slider_crank", "four_bar", "cam_roller")  # the cam's residual takes the plain rows
T = TypeVar("T")


def in_thread(task: Callable[[], T]) -> T:
    """`task()` in a thread of its own (what it keeps is its own), its kept workers released at
    its end."""
    out: list[Any] = []

    def body() -> None:
        try:
            out.append(task())
        except BaseException as error:  # re-raised in the test's thread
            out.append(error)
        finally:
            kept = getattr(kept_workers._local, "kept", None)
            if kept is not None:
                kept.release_groups()
                kept.release_truth()

    thread = threading.Thread(target=body)
    thread.start()
    thread.join()
    if isinstance(out[0], BaseException):
        raise out[0]
    return out[0]  # type: ignore[no-any-return]


def shipped(name: str) -> Group:
    """The reference engine's group of `name`, as the Dask runner ships it (no adapter)."""
    group = plan_engine(
        consistent_start(build_scenario(name)), "reference", adapters.load("reference"), True, None
    )
    return Group(group.scenario, group.engine, None, group.version, group.jobs)


def same(a: dict[str, Any], b: dict[str, Any]) -> bool:
    for column in set(a) - set(VARIES_BETWEEN_RUNS):
        x, y = a[column], b[column]
        if not (
            x == y or (isinstance(x, float) and isinstance(y, float) and math.isnan(x) and math.isnan(y))
        ):
            return False
    return True


def test_a_thread_s_tasks_share_one_fork_and_make_the_rows_of_fresh_workers() -> None:
    residual = reference_residual()

    def kept() -> tuple[list[Any], list[Any], int]:
        truths = [truth_task(independent_truth, shipped(n).scenario, 600.0) for n in SCENARIOS]
        made = [
            group_task(adapters.load, group, group.jobs, truth, CONFIG, residual)
            for group, truth in zip(map(shipped, SCENARIOS), truths, strict=True)
        ]
        return truths, made, kept_workers.forks()

    def fresh() -> tuple[list[Any], list[Any]]:  # a fork per truth and per group, as before
        truths, made = [], []
        for name in SCENARIOS:
            group = shipped(name)
            truths.append(solve_truth(independent_truth, group.scenario, 600.0))
            group.adapter = adapters.load("reference")
            made.append(run_group(group, group.jobs, truths[-1], CONFIG, residual))
        return truths, made

    truths, made, forks = in_thread(kept)
    assert forks == 2  # one child for the engine's runs, one for the truths, over three scenarios
    fresh_truths, fresh_made = in_thread(fresh)
    for truth, other in zip(truths, fresh_truths, strict=True):
        assert isinstance(truth, NamedTruth) and isinstance(other, NamedTruth)
        assert truth.name == other.name
        assert truth.trajectory.levels == other.trajectory.levels
        for level in truth.trajectory.levels:
            mine, theirs = truth.trajectory.level(level), other.trajectory.level(level)
            assert mine is not None and theirs is not None
            assert np.array_equal(mine, theirs, equal_nan=True)
        assert truth.trajectory.extras.keys() == other.trajectory.extras.keys()
        for name, values in truth.trajectory.extras.items():  # the cam's parameter, the native forces
            assert np.array_equal(values, other.trajectory.extras[name], equal_nan=True)
    rows = [row for group in made for row, _ in group]
    fresh_rows = [row for group in fresh_made for row, _ in group]
    assert len(rows) == len(fresh_rows) > len(SCENARIOS)
    assert all(same(a, b) for a, b in zip(rows, fresh_rows, strict=True))
    assert {row["status"] for row in rows} == {"ok"}
    assert all(row["constraint_residual"] >= 0 for row in rows)


def test_another_configuration_or_thread_gets_workers_of_its_own() -> None:
    group = shipped("four_bar")
    truth = solve_truth(independent_truth, group.scenario, 600.0)
    jobs = group.jobs[:1]

    def two_configurations() -> int:
        group_task(adapters.load, group, jobs, truth, CONFIG, None)
        group_task(adapters.load, group, jobs, truth, CONFIG, None)
        assert kept_workers.forks() == 1
        group_task(adapters.load, group, jobs, truth, RunConfig(repeats=2, warmup=0), None)
        return kept_workers.forks()  # the first configuration's workers released: a new fork

    assert in_thread(two_configurations) == 1
    assert in_thread(kept_workers.forks) == 0  # another thread keeps nothing of the first's


def test_a_crash_in_a_kept_truth_worker_costs_its_own_truth() -> None:
    def crashing(scenario: Any, times: np.ndarray) -> Any:
        if scenario.name == "four_bar":
            import os
            import signal

            os.kill(os.getpid(), signal.SIGKILL)
        return independent_truth(scenario, times)

    def task() -> list[Any]:
        return [
            truth_task(crashing, shipped(n).scenario, 600.0)
            for n in ("slider_crank", "four_bar", "spur_gears")
        ]

    first, crashed, after = in_thread(task)
    assert isinstance(first, NamedTruth) and isinstance(after, NamedTruth)
    assert isinstance(crashed, str) and crashed.startswith("no reference truth (crash")


@pytest.fixture(autouse=True)
def _nothing_left() -> Any:
    yield
    kept_workers.release_all()
