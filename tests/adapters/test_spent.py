"""A run that fails records what it spent up to the failure (adapters.spent), split as an ok run's
time is, into build, warm-up and timed repeats, and no run time: on a fake clock that advances by
known amounts in each call (a fake engine is fine for testing the timing), and on the native
solver at a real dead point."""

from __future__ import annotations

import math

import numpy as np
import pytest

import adapters
import scenarios
from adapters import timing
from adapters.base import WARMUP_POINTS
from adapters.failures import Singular
from reports.run.rows import result_row
from scenarios import Scenario, Trajectory
from tests.support.fake_clock import Clock
from tests.support.grid_engine import GridAdapter

BUILD, PREFIX, WHOLE = 0.3, 0.01, 0.2
"""Fake seconds of a build, of a warm-up over the grid's first interval, of a run over the grid."""


class FailingAdapter(GridAdapter):
    """Spends BUILD on its build, PREFIX on a warm-up grid and WHOLE on a whole grid, then raises
    where told: in the build, in the warm-up (its prefix and then the whole grid), in the timed run
    numbered `fail_at` (1 first), or returns NaN positions from every whole run."""

    name = "failing"

    def __init__(self, clock: Clock, where: str, fail_at: int = 1) -> None:
        super().__init__()
        self.clock, self.where, self.fail_at, self.timed_runs = clock, where, fail_at, 0

    def build(self, scenario: Scenario, setting: object) -> Scenario:  # type: ignore[override]
        self.clock.spend(BUILD)
        if self.where == "build":
            raise ValueError("no model")
        return scenario

    def simulate(self, model: Scenario, times: np.ndarray) -> Trajectory:
        short = len(times) <= WARMUP_POINTS
        self.clock.spend(PREFIX if short else WHOLE)
        if self.where == "warm-up":
            raise Singular("dead point", time=0.5)
        if not short:
            self.timed_runs += 1
            if self.where == "repeat" and self.timed_runs == self.fail_at:
                raise Singular("dead point", time=0.5)
        found = self.zeros(model, times)
        if self.where == "nan" and not short:
            found.position[-1, 0, 0] = np.nan  # type: ignore[index]
        return found


@pytest.fixture(scope="module")
def scenario() -> Scenario:
    return scenarios.load("slider_crank")


Spent = tuple[str, tuple[float, ...], float]
"""A run's status, its (build, warm-up, repeats) seconds and its run time."""


def spent_of(adapter: FailingAdapter, scenario: Scenario, warmup: int) -> Spent:
    found = adapter.run(scenario, repeats=3, warmup=warmup)
    return found.status, (found.build_time, found.warmup_time, found.repeats_time), found.run_time


@pytest.mark.parametrize(
    ("where", "fail_at", "warmup", "status", "expected"),
    [
        ("build", 1, 1, "failed", (BUILD, 0.0, 0.0)),
        ("warm-up", 1, 1, "singular", (BUILD, PREFIX + WHOLE, 0.0)),  # the prefix, then the whole grid
        ("warm-up", 1, 0, "singular", (BUILD, 0.0, WHOLE)),  # no warm-up: it fails in the first repeat
        ("repeat", 1, 1, "singular", (BUILD, PREFIX, WHOLE)),
        ("repeat", 1, 2, "singular", (BUILD, 2 * PREFIX, WHOLE)),
        ("repeat", 2, 1, "singular", (BUILD, PREFIX, 2 * WHOLE)),  # one repeat done, the second failed
        ("nan", 1, 1, "diverged", (BUILD, PREFIX, 3 * WHOLE)),  # the repeats all ran, then NaN was seen
    ],
)
def test_a_failed_run_is_charged_what_it_spent_and_shows_no_run_time(
    clock: Clock, scenario: Scenario, where: str, fail_at: int, warmup: int, status: str, expected: tuple
) -> None:
    found, times, run_time = spent_of(FailingAdapter(clock, where, fail_at), scenario, warmup)
    assert found == status
    assert times == pytest.approx(expected, abs=1e-12)
    assert math.isnan(run_time)


def test_an_ok_run_is_timed_as_before(clock: Clock, scenario: Scenario) -> None:
    found, times, run_time = spent_of(FailingAdapter(clock, "nowhere"), scenario, 1)
    assert found == "ok"
    assert times == pytest.approx((BUILD, PREFIX, 3 * WHOLE), abs=1e-12)
    assert run_time == pytest.approx(WHOLE, abs=1e-12)


def test_the_row_of_a_failed_run_stores_its_work_and_no_run_time(clock: Clock, scenario: Scenario) -> None:
    result = FailingAdapter(clock, "repeat").run(scenario, repeats=3, warmup=1)
    row = result_row(scenario, result, True, 3, 1, {}, ())
    assert row["status"] == "singular" and math.isnan(row["run_time"])
    work = (row["build_time"], row["warmup_time"], row["repeats_time"])
    assert work == pytest.approx((BUILD, PREFIX, WHOLE))
    assert (row["repeats"], row["warmup"]) == (0, 0)  # no timed repeat was made of a failed run


def test_the_native_solver_at_a_dead_point_records_the_seconds_of_its_approach() -> None:
    # a crank of 0.2 m: the four-bar meets a dead point early in the crank's turn
    scenario = scenarios.load("four_bar", {"crank_length": "0.2"})
    native = adapters.load("reference")
    before = timing.time.process_time()
    found = native.run(scenario, repeats=2, warmup=1)
    cpu = timing.time.process_time() - before
    assert found.status == "singular" and found.failure_time is not None and math.isnan(found.run_time)
    work = found.build_time + found.warmup_time + found.repeats_time
    assert found.build_time > 0 and found.repeats_time > 0
    assert 0.5 * cpu < work <= cpu  # nearly the whole call: the approach to the dead point is the work
