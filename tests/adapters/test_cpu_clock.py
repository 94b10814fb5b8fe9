"""A run's time is the process's CPU time, the wall clock's beside it (issue #40): on fake clocks
where work moves both and waiting (a machine busy with other jobs) moves the wall clock alone, the
minimum of repeats and the agreement rule are the CPU time's, and a row stores both; on the
machine's clocks, a sleeping engine spends wall time and almost no CPU time."""

from __future__ import annotations

import time

import numpy as np
import pytest

from adapters.base import WARMUP_POINTS
from adapters.timing import timed
from reports.run.rows import result_row
from scenarios import Scenario, Trajectory
from scenarios import load as load_scenario
from tests.support.fake_clock import Clock
from tests.support.grid_engine import GridAdapter


def working(clock: Clock, cpu: list[float], waits: list[float]):  # type: ignore[no-untyped-def]
    """An action that spends the next of `cpu` seconds of work, then waits the next of `waits`."""
    work, idle = iter(cpu), iter(waits)

    def action() -> None:
        clock.spend(next(work))
        clock.wait(next(idle))

    return action


def test_the_best_repeat_is_the_least_cpu_not_the_least_wall(clock: Clock) -> None:
    # the second repeat did less work but waited long behind other jobs
    found = timed(working(clock, [0.30, 0.20, 0.25], [0.0, 0.5, 0.0]), repeats=3)
    assert found.best == pytest.approx(0.20)
    assert found.best_wall == pytest.approx(0.25)  # the least wall time, the third repeat's
    assert found.repeats_time == pytest.approx(0.75) and found.repeats_time_wall == pytest.approx(1.25)


def test_two_repeats_agree_on_cpu_whatever_they_waited(clock: Clock) -> None:
    # 1 % apart in work, 10x apart in wall time: the rule (2 %) stops at the second
    found = timed(working(clock, [0.100, 0.101, 0.5], [0.0, 0.9, 0.0]), repeats=3, agree=0.02)
    assert (found.repeats, found.best) == (2, pytest.approx(0.100))


def test_a_long_first_repeat_is_judged_on_cpu(clock: Clock) -> None:
    # 1 s of wall but 0.1 s of work is not over once_above = 0.4: the repeats go on
    found = timed(working(clock, [0.1, 0.1, 0.1], [0.9, 0.0, 0.0]), repeats=3, once_above=0.4)
    assert found.repeats == 3


class WaitingAdapter(GridAdapter):
    """Builds in BUILD seconds of work and BUILD_WAIT of waiting; each simulation spends WORK per
    grid time and waits WAIT per grid time."""

    name = "waiting"
    BUILD, BUILD_WAIT, WORK, WAIT = 0.2, 0.3, 1e-3, 4e-3

    def __init__(self, clock: Clock) -> None:
        super().__init__()
        self.clock = clock

    def build(self, scenario: Scenario, setting: object) -> Scenario:  # type: ignore[override]
        self.clock.spend(self.BUILD)
        self.clock.wait(self.BUILD_WAIT)
        return scenario

    def simulate(self, model: Scenario, times: np.ndarray) -> Trajectory:
        self.clock.spend(self.WORK * len(times))
        self.clock.wait(self.WAIT * len(times))
        return self.zeros(model, times)


def test_a_row_stores_cpu_time_and_wall_time_beside_it(clock: Clock) -> None:
    scenario = load_scenario("slider_crank")
    points = len(scenario.times())
    result = WaitingAdapter(clock).run(scenario, repeats=2, warmup=1)
    row = result_row(scenario, result, True, 2, 1, {}, ())
    a = WaitingAdapter
    assert row["run_time"] == pytest.approx(a.WORK * points, rel=1e-9)
    assert row["run_time_wall"] == pytest.approx((a.WORK + a.WAIT) * points, rel=1e-9)
    assert row["build_time"] == pytest.approx(a.BUILD) and row["build_time_wall"] == pytest.approx(0.5)
    assert row["warmup_time"] == pytest.approx(a.WORK * WARMUP_POINTS, rel=1e-9)
    assert row["warmup_time_wall"] == pytest.approx((a.WORK + a.WAIT) * WARMUP_POINTS, rel=1e-9)
    assert row["repeats_time"] == pytest.approx(2 * a.WORK * points, rel=1e-9)
    assert row["repeats_time_wall"] == pytest.approx(2 * (a.WORK + a.WAIT) * points, rel=1e-9)


def test_on_the_machines_clocks_a_sleeping_engine_spends_wall_time_not_cpu() -> None:
    nap = 0.05
    found = timed(lambda: time.sleep(nap), repeats=2)
    assert found.best_wall >= nap and found.best < nap / 5
    spun = timed(lambda: sum(range(300_000)), repeats=2)  # work: both clocks move alike
    assert spun.best > 0 and spun.best <= spun.best_wall * 1.5 + 1e-3
