"""What a run's timing spent is measured, not estimated (issue #27): on a fake clock that advances
by known amounts in each call, `timed` sums the warm-up calls and the timed repeats as they ran,
and an engine run's RunResult carries them (the warm-up over the grid's first interval costs the
prefix's time, not the run time again). A fake clock and a fake adapter are fine for testing the
timing; a real sleep checks the same on the machine's clock."""

from __future__ import annotations

import math
import time

import numpy as np
import pytest

from adapters.base import WARMUP_POINTS
from adapters.timing import fastest, timed
from scenarios import Scenario, Trajectory
from scenarios import load as load_scenario
from tests.support.fake_clock import Clock
from tests.support.grid_engine import GridAdapter

PER_POINT = 1e-3
"""Seconds a ClockAdapter's simulation spends per grid time on the fake clock."""


def spending(clock: Clock, seconds: list[float], calls: list[str], name: str):  # type: ignore[no-untyped-def]
    """An action that spends the next of `seconds` on the clock at each call, and says it was called."""
    left = iter(seconds)

    def action() -> str:
        calls.append(name)
        clock.spend(next(left))
        return name

    return action


def test_the_warm_up_and_the_repeats_are_summed_as_they_ran(clock: Clock) -> None:
    calls: list[str] = []
    warm = spending(clock, [0.25, 0.5], calls, "warm")
    action = spending(clock, [0.3, 0.1, 0.2], calls, "action")
    found = timed(action, repeats=3, warmup=2, warm=warm)
    assert calls == ["warm", "warm", "action", "action", "action"]
    assert found.warmup_time == pytest.approx(0.75, abs=1e-15)
    assert found.repeats_time == pytest.approx(0.6, abs=1e-15)  # not 3 x the minimum (0.3)
    assert (found.best, found.repeats, found.result) == (pytest.approx(0.1), 3, "action")


def test_without_a_warm_up_it_took_no_time(clock: Clock) -> None:
    found = timed(spending(clock, [0.2, 0.4], [], "action"), repeats=2)
    assert found.warmup_time == 0.0 and found.repeats_time == pytest.approx(0.6, abs=1e-15)


def test_the_action_warms_itself_when_no_cheaper_warm_up_is_given(clock: Clock) -> None:
    found = timed(spending(clock, [0.7, 0.2], [], "action"), repeats=1, warmup=1)
    assert (found.warmup_time, found.repeats_time, found.best) == pytest.approx((0.7, 0.2, 0.2))


def test_a_long_first_repeat_is_the_only_one_and_the_whole_of_the_repeats_time(clock: Clock) -> None:
    found = timed(spending(clock, [0.5, 0.1, 0.1], [], "action"), repeats=3, once_above=0.4)
    assert (found.repeats, found.repeats_time, found.best) == (1, pytest.approx(0.5), pytest.approx(0.5))


def test_repeats_stop_where_one_agrees_with_the_best_before_it(clock: Clock) -> None:
    found = timed(spending(clock, [0.100, 0.1015, 0.5], [], "action"), repeats=3, agree=0.02)
    assert (found.repeats, found.best) == (2, pytest.approx(0.100))  # 1.5 % apart: the third never ran
    assert found.repeats_time == pytest.approx(0.2015)


def test_repeats_that_disagree_go_on_to_the_count(clock: Clock) -> None:
    found = timed(spending(clock, [0.100, 0.103, 0.0995, 0.5], [], "action"), repeats=3, agree=0.02)
    assert (found.repeats, found.best) == (3, pytest.approx(0.0995))  # 3 % apart, then the count


def test_agreement_is_relative_to_the_smaller_of_the_two(clock: Clock) -> None:
    # 0.1019 against 0.100 is 1.9 % of the smaller and 1.86 % of the larger
    assert timed(spending(clock, [0.1019, 0.100, 0.1], [], "a"), repeats=3, agree=0.0192).repeats == 2
    assert timed(spending(clock, [0.1019, 0.100, 0.1], [], "a"), repeats=3, agree=0.0188).repeats == 3


def test_repeats_are_made_while_one_more_fits_the_budget(clock: Clock) -> None:
    # after three of 0.1 s a fourth would spend 0.4 s, past the budget of 0.35 s
    found = timed(spending(clock, [0.1] * 10, [], "action"), repeats=10, budget=0.35)
    assert (found.repeats, found.repeats_time) == (3, pytest.approx(0.3))


def test_a_repeat_longer_than_half_the_budget_is_the_only_one(clock: Clock) -> None:
    found = timed(spending(clock, [0.2, 0.1, 0.1], [], "action"), repeats=3, budget=0.35)
    assert (found.repeats, found.best) == (1, pytest.approx(0.2))


def test_the_budget_counts_the_best_not_the_first(clock: Clock) -> None:
    # 0.1 then 0.05: a third as long as the best fits 0.24 s (0.2), one as long as the first would not
    found = timed(spending(clock, [0.1, 0.05, 0.04, 0.5], [], "action"), repeats=3, budget=0.24)
    assert (found.repeats, found.best) == (3, pytest.approx(0.04))


@pytest.mark.parametrize("each", [0.011, 0.051, 0.09, 0.13, 0.2, 0.26, 0.6])
def test_the_repeats_cost_at_most_the_budget_or_one_repeat(clock: Clock, each: float) -> None:
    found = timed(spending(clock, [each] * 40, [], "action"), repeats=40, budget=0.25)
    assert found.repeats_time <= max(0.25, each) + 1e-12
    assert found.repeats == max(1, int(0.25 / each + 1e-9))  # as many as fit


def test_without_agree_equal_repeats_all_run(clock: Clock) -> None:
    assert timed(spending(clock, [0.1, 0.1, 0.1], [], "action"), repeats=3).repeats == 3


def test_repeats_of_several_calls_sum_every_call(clock: Clock) -> None:
    found = timed(spending(clock, [0.1] * 4, [], "action"), repeats=2, number=2)
    assert found.repeats_time == pytest.approx(0.4, abs=1e-15)
    assert found.best == pytest.approx(0.1, abs=1e-15)  # per call


def test_fastest_is_timed_best_and_result(clock: Clock) -> None:
    assert fastest(spending(clock, [0.3, 0.2], [], "action"), repeats=2) == (pytest.approx(0.2), "action")


class ClockAdapter(GridAdapter):
    """Spends PER_POINT seconds of the fake clock per grid time it simulates; `short` 'raise' makes
    a grid of WARMUP_POINTS times raise after spending its time (an engine that cannot take one)."""

    name = "clock"

    def __init__(self, clock: Clock, short: str = "ok") -> None:
        super().__init__()
        self.clock, self.short = clock, short

    def simulate(self, model: Scenario, times: np.ndarray) -> Trajectory:
        self.clock.spend(PER_POINT * len(times))
        if self.short == "raise" and len(times) <= WARMUP_POINTS:
            raise ValueError("a grid of fewer than three times")
        return self.zeros(model, times)


@pytest.fixture(scope="module")
def scenario() -> Scenario:
    return load_scenario("slider_crank")


def test_a_runs_warm_up_time_is_the_first_intervals_not_the_run_time_again(clock: Clock, scenario) -> None:
    points = len(scenario.times())
    result = ClockAdapter(clock).run(scenario, repeats=3, warmup=2)
    assert result.status == "ok", result.message
    assert result.warmup_time == pytest.approx(2 * WARMUP_POINTS * PER_POINT, rel=1e-9)
    assert result.repeats_time == pytest.approx(3 * points * PER_POINT, rel=1e-9)
    assert result.run_time == pytest.approx(points * PER_POINT, rel=1e-9)
    assert result.build_time == 0.0


def test_a_warm_up_that_falls_back_to_the_whole_grid_counts_both(clock: Clock, scenario) -> None:
    points = len(scenario.times())
    result = ClockAdapter(clock, short="raise").run(scenario, repeats=1, warmup=1)
    assert result.status == "ok", result.message
    assert result.warmup_time == pytest.approx((WARMUP_POINTS + points) * PER_POINT, rel=1e-9)


def test_a_failed_run_records_what_it_spent_and_no_run_time(clock: Clock, scenario) -> None:
    result = ClockAdapter(clock, short="raise").run(scenario, times=[0.0, 0.1], repeats=1, warmup=1)
    assert result.status == "failed" and math.isnan(result.run_time)
    # the warm-up's prefix raised, then the whole grid (the same two times): both in the warm-up
    assert result.warmup_time == pytest.approx(2 * 2 * PER_POINT, rel=1e-9)
    assert (result.build_time, result.repeats_time) == (0.0, 0.0)


def test_on_the_machines_clock_the_warm_up_time_is_the_sleep_it_made() -> None:
    """A warm-up that sleeps 50 ms twice took at least 0.1 s of wall time, and not three times as
    long; a sleep is no work, so its CPU time is far below the nap."""
    nap = 0.05
    found = timed(lambda: None, repeats=2, warmup=2, warm=lambda: time.sleep(nap))
    assert 2 * nap <= found.warmup_time_wall < 3 * 2 * nap
    assert 0 <= found.warmup_time < nap
    assert 0 <= found.repeats_time < nap and 0 <= found.repeats_time_wall < nap
