"""A row whose truth could not be made is still judged by its own figures: its energy balance and
its step halving (scoring.self_check), made in the runner's worker. The fake engine's x is off by
its step dt, so half the step moves it by dt / 2: 0.005 m (0.025 characteristic lengths, past the
limit) at dt = 0.01 and 0.0005 m (0.0025, inside it) at dt = 0.001. (A fake is fine for testing
the runner.)"""

from __future__ import annotations

import numpy as np
import pytest

from reports.run.runner import RunConfig, Runner
from reports.scoring import self_check
from reports.store.results_store import ResultsStore, read_results
from scenarios import Scenario, Trajectory
from tests.support.fake_engine import fake_loader


def no_truth(scenario: Scenario, times: np.ndarray) -> Trajectory:
    raise RuntimeError("no truth for this scenario")


def test_an_unjudged_row_is_halved_and_marked_past_the_limit(tmp_path) -> None:
    store = ResultsStore(tmp_path)
    config = RunConfig(repeats=1, warmup=0, timeout=30.0, ladder=True)
    runner = Runner(
        store, ["fake"], config, loader=fake_loader(tmp_path / "log"), truth=no_truth, progress=False
    )
    runner.run(["slider_crank"])
    frame, _ = read_results(tmp_path)
    good = frame[(frame["mode"] == "good") & (frame["status"] == "ok")].set_index("setting")
    coarse, fine = good.loc["good dt=0.01"], good.loc["good dt=0.001"]
    assert coarse["step_halving"] == pytest.approx(0.025, rel=1e-9)
    assert fine["step_halving"] == pytest.approx(0.0025, rel=1e-9)
    assert fine["step_halving"] < self_check.STEP_LIMIT < coarse["step_halving"]
    assert "at half the step" in coarse["self_check"] and fine["self_check"] == ""
