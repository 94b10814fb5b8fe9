"""The untimed warm-up covers the grid's first interval only, and the timed runs the whole grid
(issue #27): a fake adapter records the grids it is given (a fake is fine for testing the runner);
a real engine's result is the same bit for bit with the prefix warm-up as with none."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

import adapters
from adapters.base import WARMUP_POINTS, Diverged, Setting
from adapters.timing import fastest
from reports.run.group_runs import LONG_RUN, REPEATS_BUDGET, RunConfig, timed_run
from scenarios import Scenario, Trajectory
from scenarios import load as load_scenario
from tests.support.busy import work
from tests.support.grid_engine import GridAdapter


class RecordingAdapter(GridAdapter):
    """Records the grid of every simulate call; `short` says how it treats a grid of fewer than
    three times ('ok', or 'raise' like an engine that cannot take one); `diverge_at` makes it
    raise Diverged at that grid index (as the runner's fake does: IndexError on a shorter grid);
    `sleep` seconds per call on a grid longer than WARMUP_POINTS (a tuple: in turn, call by call)."""

    name = "recording"

    def __init__(
        self, short: str = "ok", diverge_at: int | None = None, sleep: float | tuple[float, ...] = 0.0
    ) -> None:
        super().__init__()
        self.grids: list[np.ndarray] = []
        self.short, self.diverge_at = short, diverge_at
        self.sleeps = itertools.cycle(sleep if isinstance(sleep, tuple) else (sleep,))

    def simulate(self, model: Scenario, times: np.ndarray) -> Trajectory:
        self.grids.append(np.array(times, copy=True))
        if self.short == "raise" and len(times) < 3:
            raise ValueError("a grid of fewer than three times")
        if self.diverge_at is not None:  # IndexError on a grid too short to reach it
            raise Diverged("state exploded", time=float(times[self.diverge_at]))
        if len(times) > WARMUP_POINTS:
            work(next(self.sleeps))
        self.count_steps(len(times) - 1)
        return self.zeros(model, times)


@pytest.fixture(scope="module")
def scenario() -> Scenario:
    return load_scenario("slider_crank")


def lengths(adapter: RecordingAdapter) -> list[int]:
    return [len(grid) for grid in adapter.grids]


def test_the_warm_up_simulates_the_first_interval_and_the_timed_runs_the_whole_grid(scenario) -> None:
    adapter = RecordingAdapter()
    grid = np.asarray(scenario.times())
    result = adapter.run(scenario, repeats=3, warmup=2)
    assert result.status == "ok"
    assert lengths(adapter) == [2, 2, len(grid), len(grid), len(grid)]
    for warm in adapter.grids[:2]:
        assert np.array_equal(warm, grid[:2])
    for timed in adapter.grids[2:]:
        assert np.array_equal(timed, grid)
    assert result.steps == len(grid) - 1  # the steps of a timed run, not of the warm-up's
    assert result.trajectory is not None and len(result.trajectory.times) == len(grid)


def test_no_warm_up_means_no_prefix_run(scenario) -> None:
    adapter = RecordingAdapter()
    adapter.run(scenario, repeats=2, warmup=0)
    assert lengths(adapter) == [len(scenario.times())] * 2


def test_a_grid_given_to_run_is_the_one_whose_prefix_warms(scenario) -> None:
    adapter = RecordingAdapter()
    grid = np.linspace(0.5, 0.9, 5)
    adapter.run(scenario, times=grid, repeats=1, warmup=1)
    assert [list(g) for g in adapter.grids] == [list(grid[:2]), list(grid)]


def test_a_grid_of_one_time_is_its_own_prefix(scenario) -> None:
    adapter = RecordingAdapter()
    assert adapter.run(scenario, times=[0.0], repeats=1, warmup=1).status == "ok"
    assert lengths(adapter) == [1, 1]


def test_an_engine_that_cannot_take_the_prefix_is_warmed_on_the_whole_grid(scenario) -> None:
    adapter = RecordingAdapter(short="raise")
    n = len(scenario.times())
    result = adapter.run(scenario, repeats=2, warmup=1)
    assert result.status == "ok", result.message
    assert lengths(adapter) == [2, n, n, n]


def test_a_failure_is_the_whole_runs_not_the_prefixs(scenario) -> None:
    """The prefix cannot reach grid index 3 (it raises IndexError there, as the runner's fake
    does): the row says what the whole grid's run says, Diverged at the grid's fourth time."""
    adapter = RecordingAdapter(diverge_at=3)
    grid = np.asarray(scenario.times())
    result = adapter.run(scenario, repeats=3, warmup=1)
    assert result.status == "diverged"
    assert result.failure_time == pytest.approx(float(grid[3]))
    assert lengths(adapter) == [2, len(grid)]  # the whole grid's warm-up raised: no timed run


def test_fastest_times_the_action_not_the_warm_up() -> None:
    calls: list[str] = []

    def warm() -> None:
        calls.append("warm")
        work(0.05)

    def action() -> int:
        calls.append("action")
        return 7

    best, result = fastest(action, repeats=3, warmup=2, warm=warm)
    assert calls == ["warm", "warm", "action", "action", "action"]
    assert result == 7 and best < 0.05
    calls.clear()
    fastest(action, repeats=1, warmup=1)  # without `warm`, the action warms itself
    assert calls == ["action", "action"]


def test_the_harness_times_the_whole_grid_after_a_prefix_warm_up(scenario) -> None:
    config = RunConfig(repeats=3, warmup=1)
    grid = np.asarray(scenario.times())
    short = RecordingAdapter(sleep=(0.001, 0.02))  # repeats 20 times apart: they never agree
    result, repeats = timed_run(short, scenario, short.default_setting(scenario), grid, config)
    assert (result.status, repeats) == ("ok", 3)
    assert lengths(short) == [2, len(grid), len(grid), len(grid)]
    long = RecordingAdapter(sleep=LONG_RUN * 1.2)  # a run longer than LONG_RUN is timed once
    result, repeats = timed_run(long, scenario, long.default_setting(scenario), grid, config)
    assert (result.status, repeats) == ("ok", 1)
    assert lengths(long) == [2, len(grid)]
    assert result.run_time > LONG_RUN


def test_the_harness_makes_no_repeat_past_its_budget(scenario) -> None:
    """Runs under LONG_RUN whose repeats never agree (6 % apart): one of 0.6 of REPEATS_BUDGET is
    timed once (a second would pass the budget), one of 0.4 of it twice, one of 0.2 of it three
    times (the count); each run's repeats within the budget or one repeat."""
    config = RunConfig(repeats=3, warmup=1)
    grid = np.asarray(scenario.times())
    for share, expected in ((0.6, 1), (0.4, 2), (0.2, 3)):
        first = share * REPEATS_BUDGET
        adapter = RecordingAdapter(sleep=(first, first * 1.06))
        result, repeats = timed_run(adapter, scenario, adapter.default_setting(scenario), grid, config)
        assert (result.status, repeats) == ("ok", expected), share
        assert result.repeats_time <= max(REPEATS_BUDGET, result.run_time) * 1.05, share


def same(a: Trajectory, b: Trajectory) -> bool:
    """Bit for bit: times, every level and every extra column."""
    if not np.array_equal(a.times, b.times) or a.bodies != b.bodies or a.levels != b.levels:
        return False
    if any(not np.array_equal(a.level(k), b.level(k)) for k in a.levels):  # type: ignore[arg-type]
        return False
    return a.extras.keys() == b.extras.keys() and all(
        np.array_equal(a.extras[k], b.extras[k]) for k in a.extras
    )


@pytest.mark.parametrize(
    ("engine", "name", "mode"),
    [
        ("reference", "slider_crank", None),
        ("reference", "compound_pendulum", None),
        ("reference", "compound_pendulum", "ali3p"),
        ("mujoco", "slider_crank", None),
        ("exudyn", "slider_crank", None),
        ("pinocchio", "four_bar", None),
        ("pinocchio", "compound_pendulum", None),
    ],
)
def test_a_real_engines_result_is_the_same_after_the_prefix_warm_up_as_after_none(engine, name, mode) -> None:
    adapter = adapters.load(engine)
    scenario = load_scenario(name)
    setting = adapter.default_setting(scenario) if mode is None else Setting.of(mode)
    cold = adapter.run(scenario, setting, repeats=1, warmup=0)
    warmed = adapters.load(engine).run(scenario, setting, repeats=1, warmup=1)
    assert cold.status == warmed.status == "ok", (cold.message, warmed.message)
    assert cold.trajectory is not None and warmed.trajectory is not None
    assert same(cold.trajectory, warmed.trajectory)
    assert cold.steps == warmed.steps
