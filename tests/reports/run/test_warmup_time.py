"""Each row holds the seconds its warm-up and its timed repeats took (issue #27), measured in the
worker where they ran: a fake engine whose warm-up (the grid's first interval) sleeps a known time
and whose timed run sleeps another gives rows whose warmup_time is the warm-up's sleeps, not the
run time again. A store written before the columns existed loads, resumes, renders and passes the
gate, its rows holding NaN for what they never recorded. (A fake is fine for testing the runner.)"""

from __future__ import annotations

import math
import shutil
from pathlib import Path

import pandas as pd
import pytest

from adapters.base import RunResult
from reports.gate.gate import baseline_cells, judge
from reports.run.rows import result_row
from reports.store.results_store import ResultsStore, read_results
from scenarios import load as load_scenario
from tests.support.fake_engine import GOOD
from tests.support.sleeper import RUN, SCENARIO, WARM, run_sleeper
from tests.support.stores import write_schema_1

NEW = ("warmup_time", "repeats_time")


@pytest.fixture(scope="module")
def made(tmp_path_factory: pytest.TempPathFactory) -> Path:
    directory = tmp_path_factory.mktemp("warmtime") / "store"
    run_sleeper(directory)
    return directory


def test_a_rows_warmup_time_is_its_warm_ups_sleeps_not_the_run_time_again(made: Path) -> None:
    frame, _ = read_results(made)
    row = frame[frame["engine"] == "sleeper"].iloc[0]
    assert (row["status"], row["warmup"], row["repeats"]) == ("ok", 2, 3)
    assert 2 * WARM <= row["warmup_time"] < 3 * 2 * WARM
    assert 3 * RUN <= row["repeats_time"] < 3 * 3 * RUN
    assert row["repeats_time"] >= 3 * row["run_time"]  # a sum is at least the count x the minimum
    assert row["warmup_time"] > 2 * row["run_time"]  # what run_time x warmup would have estimated


def test_every_ok_row_has_them_and_a_failed_one_none(made: Path) -> None:
    frame, _ = read_results(made)
    ok = frame[frame["status"] == "ok"]
    assert len(ok) == 2 and (ok[list(NEW)] >= 0).all().all()
    raised = RunResult("fake", "0", GOOD[0], "failed", message="RuntimeError")  # nothing timed
    failed = result_row(load_scenario(SCENARIO), raised, False, 0, 0, {}, ())
    assert all(math.isnan(failed[c]) for c in NEW)


@pytest.fixture(scope="module")
def old(made: Path, tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The same rows as a store from before the columns: one results.parquet without them."""
    return write_schema_1(tmp_path_factory.mktemp("old") / "store", made, without=NEW)


def test_an_old_store_loads_with_the_columns_not_recorded(old: Path) -> None:
    assert not set(NEW) & set(pd.read_parquet(old / "results.parquet").columns)
    frame, _ = read_results(old)
    assert frame[list(NEW)].isna().all().all()
    store = ResultsStore(old)
    assert all(math.isnan(r[c]) for r in store.rows.values() for c in NEW)


def test_an_old_store_resumes_and_the_new_rows_hold_the_columns(old: Path, tmp_path: Path) -> None:
    directory = tmp_path / "resumed"
    shutil.copytree(old, directory, symlinks=True)
    store = ResultsStore(directory)
    del store.rows[(SCENARIO, "sleeper", GOOD[1].label)]  # as if interrupted before that run
    store.save(store.meta)
    run_sleeper(directory)
    frame, _ = read_results(directory)
    rows = frame.set_index("engine")
    assert math.isnan(rows.loc["fake", "warmup_time"])  # kept from the old store, as it was
    assert 2 * WARM <= rows.loc["sleeper", "warmup_time"] < 3 * 2 * WARM  # run again: recorded
    before, _ = read_results(old)
    assert judge(baseline_cells(before), frame).regressions == ()  # the gate passes either way
    assert judge(baseline_cells(frame), before).regressions == ()


def test_an_old_store_renders(old: Path, tmp_path: Path) -> None:
    from reports.render.report import render_reports

    render_reports(old, tmp_path)
    assert (tmp_path / "summary.md").read_text()
