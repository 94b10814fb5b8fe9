"""A failed run's row holds what it spent (issue #27), measured in the worker where it ran: a fake
engine whose timed run works a known CPU time and then raises gives a row whose repeats_time is
that work (two-sided), whose run_time is empty (no failed run shows a time), and a run that hangs past
the time limit a row whose repeats_time is the limit. (A fake is fine for testing the runner.)"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from adapters.base import WARMUP_POINTS, Adapter, Setting
from reports.run.runner import RunConfig, Runner
from reports.store.results_store import ResultsStore, read_results
from scenarios import Scenario, Trajectory
from tests.support.busy import work
from tests.support.fake_engine import FakeAdapter, fake_loader, fake_truth

SCENARIO = "slider_crank"
WARM, RUN = 0.05, 0.2
"""CPU seconds a SlowFailer works in its warm-up run and in its timed run before it raises."""
CONFIG = RunConfig(ladder=True, repeats=3, warmup=1, timeout=4.0)
"""A wall-clock limit the work keeps well under on a loaded machine."""


class SlowFailer(FakeAdapter):
    """Mode 'raise' works WARM CPU seconds in a warm-up run and RUN in a timed one, which then raises;
    mode 'hang' never returns."""

    name = "slowfail"

    def ladder(self, scenario: Scenario) -> list[Setting]:
        return [Setting.of("raise"), Setting.of("hang")]

    def default_setting(self, scenario: Scenario) -> Setting:
        return Setting.of("raise")

    def simulate(self, model: tuple[Scenario, Setting], times: np.ndarray) -> Trajectory:
        if model[1].mode == "raise":
            work(WARM if len(times) <= WARMUP_POINTS else RUN)
            if len(times) <= WARMUP_POINTS:
                return super().simulate((model[0], Setting.of("good", dt=0.01)), times)
        return super().simulate(model, times)


@pytest.fixture(scope="module")
def rows(tmp_path_factory: pytest.TempPathFactory) -> pd.DataFrame:
    directory = tmp_path_factory.mktemp("failedwork") / "store"
    log = directory.parent / "fakes.log"
    known = fake_loader(log)

    def load(name: str) -> Adapter:
        return SlowFailer(log) if name == "slowfail" else known(name)

    runner = Runner(
        ResultsStore(directory),
        ["slowfail"],
        CONFIG,
        loader=load,
        truth=fake_truth,
        progress=False,
        suite="test",
    )
    runner.run([SCENARIO])
    found, _ = read_results(directory)
    return found.set_index("setting")


def test_a_failed_run_holds_its_warm_up_and_the_failing_repeat_and_no_run_time(rows: pd.DataFrame) -> None:
    row = rows.loc[Setting.of("raise").label]
    assert row["status"] == "failed" and "engine internal error" in row["message"]
    assert WARM <= row["warmup_time"] < 3 * WARM
    assert RUN <= row["repeats_time"] < 3 * RUN  # the one repeat it made, which raised
    assert 0 <= row["build_time"] < 0.05
    assert math.isnan(row["run_time"]) and row["repeats"] == 0


def test_a_timed_out_run_holds_the_limit_it_hit(rows: pd.DataFrame) -> None:
    row = rows.loc[Setting.of("hang").label]
    assert row["status"] == "timeout"
    assert row["repeats_time"] == row["repeats_time_wall"] == CONFIG.timeout
    assert math.isnan(row["run_time"])
