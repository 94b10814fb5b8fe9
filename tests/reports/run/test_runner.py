"""The runner with a fake engine that crashes, hangs, diverges, returns NaN and raises: every other
row survives, each failure is recorded with its reason, and a resumed run redoes nothing stored."""

from __future__ import annotations

import dataclasses
import math
import shutil
from pathlib import Path

import pandas as pd
import pytest

from reports.run.runner import HOOK_TRUTH, RunConfig, Runner
from reports.store.results_store import TRUTH, ResultsStore, read_results, read_trajectories
from tests.support.fake_engine import BAD, GOOD, fake_loader, fake_truth

SCENARIO = "slider_crank"
CONFIG = RunConfig(repeats=2, warmup=1, timeout=1.5)


def run(directory: Path, log: Path, config: RunConfig = CONFIG, engines=("fake", "absent")) -> None:
    store = ResultsStore(directory)
    runner = Runner(
        store, engines, config, loader=fake_loader(log), truth=fake_truth, progress=False, suite="test"
    )
    runner.run([SCENARIO])


@pytest.fixture(scope="module")
def first_run(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path, pd.DataFrame]:
    directory = tmp_path_factory.mktemp("results")
    log = directory / "calls.log"
    run(directory, log)
    frame, _ = read_results(directory)
    return directory, log, frame.set_index("setting")


def fake_rows(frame: pd.DataFrame) -> pd.DataFrame:
    return frame[frame["engine"] == "fake"]


def test_every_setting_has_a_row_with_its_status(first_run) -> None:
    _, _, frame = first_run
    rows = fake_rows(frame)
    assert sorted(rows.index) == sorted(s.label for s in (*GOOD, *BAD))
    expected = {
        "good dt=0.01": "ok",
        "good dt=0.001": "ok",
        "crash": "failed",
        "hang": "timeout",
        "diverge": "diverged",
        "nan": "diverged",
        "raise": "failed",
    }
    assert rows["status"].to_dict() == expected


def test_failures_carry_their_reason(first_run) -> None:
    rows = fake_rows(first_run[2])
    assert "SIGSEGV" in rows.loc["crash", "message"]
    assert "time limit of 1.5 s" in rows.loc["hang", "message"]
    assert "state exploded" in rows.loc["diverge", "message"]
    assert rows.loc["diverge", "failure_time"] > 0
    assert "non-finite" in rows.loc["nan", "message"]
    assert "RuntimeError: engine internal error" in rows.loc["raise", "message"]
    for label in ("crash", "hang", "diverge", "nan", "raise"):
        assert math.isnan(rows.loc[label, "error"])
        assert math.isnan(rows.loc[label, "run_time"])


def test_good_runs_survive_with_their_known_errors(first_run) -> None:
    rows = fake_rows(first_run[2])
    for setting in GOOD:
        row = rows.loc[setting.label]
        dt = setting["dt"]
        assert row["position_length_max"] == pytest.approx(dt, rel=1e-9)
        assert row["position_angle_max"] == 0.0
        assert row["velocity_length_max"] == 0.0
        assert row["error"] == pytest.approx(dt / row["characteristic_length"], rel=1e-9)
        assert math.isnan(row["acceleration_length_max"])  # the fake gives no accelerations
        assert row["levels"] == "position,velocity"
        assert row["error_position"] == row["error"] and row["error_velocity"] == 0.0
        assert math.isnan(row["error_acceleration"])  # a level not produced is NaN, never zero
        assert row["truth"] == HOOK_TRUTH  # the fake hook returns a bare trajectory
        assert row["run_time"] > 0 and row["build_time"] >= 0
        assert row["steps"] == 200 and row["repeats"] == 2
    assert list(rows.index[rows["is_default"]]) == ["good dt=0.001"]


def test_an_absent_engine_costs_its_own_row_only(first_run) -> None:
    frame = first_run[2]
    absent = frame[frame["engine"] == "absent"]
    assert len(absent) == 1
    assert absent["status"].item() == "failed"
    assert "not installed" in absent["message"].item()


def test_default_trajectory_and_truth_are_stored(first_run) -> None:
    stored = read_trajectories(first_run[0])
    assert set(stored) == {(SCENARIO, "fake", "good dt=0.001"), (SCENARIO, TRUTH, HOOK_TRUTH)}
    assert stored[(SCENARIO, "fake", "good dt=0.001")].levels == ("position", "velocity")


def test_a_resumed_run_redoes_only_the_missing_rows(first_run, tmp_path: Path) -> None:
    source, _, _ = first_run
    directory = tmp_path / "resumed"
    shutil.copytree(source, directory, symlinks=True, ignore=shutil.ignore_patterns("calls.log"))
    frame, meta = read_results(directory)
    store = ResultsStore(directory)
    del store.rows[(SCENARIO, "fake", "good dt=0.01")]  # as if interrupted before that run
    store.save(meta)
    log = directory / "calls.log"
    run(directory, log, dataclasses.replace(CONFIG, keep_failures=True))  # failures kept, not retried
    assert log.read_text().splitlines() == [f"{SCENARIO} good dt=0.01"] * 3  # warm-up + 2 repeats
    after, _ = read_results(directory)
    assert len(after) == len(frame)
    assert set(after["status"]) == set(frame["status"])


def test_a_later_plan_reconciles_the_stored_rows(first_run, tmp_path: Path) -> None:
    """A quick (default-only) run keeps the stored sweep; an engine that became available loses
    its 'unavailable' row and gains its runs."""
    source, log, frame = first_run
    directory = tmp_path / "later"
    shutil.copytree(source, directory, symlinks=True)
    available = fake_loader(log)

    def loader(name: str):  # type: ignore[no-untyped-def]
        return available("fake" if name == "absent" else name)

    store = ResultsStore(directory)
    quick = RunConfig(ladder=False, repeats=1, warmup=0, timeout=5.0)
    Runner(store, ["fake", "absent"], quick, loader=loader, truth=fake_truth, progress=False).run([SCENARIO])
    after, _ = read_results(directory)
    fake = after[after["engine"] == "fake"]
    assert sorted(fake["setting"]) == sorted(frame[frame["engine"] == "fake"].index)
    assert list(fake.loc[fake["is_default"], "setting"]) == ["good dt=0.001"]
    absent = after[after["engine"] == "absent"]
    assert list(absent["setting"]) == ["good dt=0.001"] and list(absent["status"]) == ["ok"]


def test_rerun_redoes_stored_rows(first_run, tmp_path: Path) -> None:
    log = tmp_path / "calls.log"
    config = RunConfig(ladder=False, repeats=1, warmup=0, timeout=5.0)
    run(tmp_path, log, config, engines=("fake",))
    run(tmp_path, log, config, engines=("fake",))
    assert len(log.read_text().splitlines()) == 1
    run(tmp_path, log, RunConfig(ladder=False, repeats=1, warmup=0, timeout=5.0, rerun=True), ("fake",))
    assert len(log.read_text().splitlines()) == 2


def test_the_progress_bar_counts_the_rows_the_run_says_it_made(tmp_path: Path, monkeypatch) -> None:
    """An absent engine's row is made without a run: the bar counts it too, so that its total and
    its count at the end are the run's last line's number of rows."""
    import reports.run.runner as runner_module

    bars = []
    made = runner_module.progress_bar

    def recorded(total: int, shown: bool, unit: str):  # type: ignore[no-untyped-def]
        bars.append(made(total, shown, unit))
        return bars[-1]

    monkeypatch.setattr(runner_module, "progress_bar", recorded)
    runner = Runner(
        ResultsStore(tmp_path / "r"), ("fake", "absent"), CONFIG, loader=fake_loader(tmp_path / "log"),
        truth=fake_truth, progress=True, suite="test",
    )  # fmt: skip
    runner.run([SCENARIO])
    assert runner.made["failed"] >= 1  # the absent engine's row
    assert bars[0].total == bars[0].n == runner.made.total()
