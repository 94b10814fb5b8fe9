"""A fake engine whose warm-up and timed runs spend known CPU times (tests.support.busy), and a
run of the runner with it, for the tests of what a row says its timing spent (a fake is fine for
testing the runner)."""

from __future__ import annotations

import itertools
from pathlib import Path

import numpy as np

from adapters.base import WARMUP_POINTS, Adapter, Setting
from reports.run.runner import RunConfig, Runner
from reports.store.results_store import ResultsStore
from scenarios import Scenario, Trajectory
from tests.support.busy import work
from tests.support.fake_engine import GOOD, FakeAdapter, fake_loader, fake_truth

SCENARIO = "slider_crank"
WARM, RUN = 0.06, 0.01
"""CPU seconds a Sleeper spends in a warm-up run (a grid of WARMUP_POINTS times) and in a timed run
(RUN and 2 x RUN in turn, so that no two repeats agree and a row makes all its repeats)."""
CONFIG = RunConfig(ladder=False, repeats=3, warmup=2, timeout=20.0)


class Sleeper(FakeAdapter):
    """The fake at its default setting, working WARM in a warm-up run and RUN or 2 x RUN in a
    timed one (named for the sleeps it made before runs were timed on the CPU clock)."""

    name = "sleeper"
    timed_sleeps = itertools.cycle((RUN, 2 * RUN))

    def ladder(self, scenario: Scenario) -> list[Setting]:
        return [GOOD[1]]

    def simulate(self, model: tuple[Scenario, Setting], times: np.ndarray) -> Trajectory:
        work(WARM if len(times) <= WARMUP_POINTS else next(self.timed_sleeps))
        return super().simulate(model, times)


def loader(log: Path):  # type: ignore[no-untyped-def]
    """The fakes' loader (tests.support.fake_engine) that knows the sleeper too."""
    known = fake_loader(log)

    def load(name: str) -> Adapter:
        return Sleeper(log) if name == "sleeper" else known(name)

    return load


def run_sleeper(
    directory: Path, engines: tuple[str, ...] = ("sleeper", "fake"), config: RunConfig = CONFIG
) -> None:
    """The runner's run of SCENARIO with `engines` into the store in `directory`, against the fake truth."""
    store = ResultsStore(directory)
    log = directory.parent / f"{directory.name}.log"
    runner = Runner(
        store, engines, config, loader=loader(log), truth=fake_truth, progress=False, suite="test"
    )
    runner.run([SCENARIO])
