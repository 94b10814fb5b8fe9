"""Runs fork from a warm process: the native kernels and the scenario's program are in the parent
before the first fork, a crash or a hang still costs its own row with the next run unharmed, and
the rows are those of the cold path, where each forked run loaded the kernels itself."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from adapters.base import Adapter, Setting
from reports.run import warm
from reports.run.isolation import run_isolated
from reports.run.runner import RunConfig, Runner
from reports.store.results_store import KEY, ResultsStore, read_results
from scenarios import Scenario
from scenarios import load as build_scenario
from tests.support.fake_engine import GOOD, fake_loader, fake_truth
from tests.support.run_columns import VARIES_BETWEEN_RUNS

CONFIG = RunConfig(ladder=True, repeats=1, warmup=0, timeout=3.0)


def test_a_forked_run_inherits_the_warmed_kernels_and_program() -> None:
    from reference_solver.compiled import loop, path

    scenario = build_scenario("four_bar[omega=33]")
    warm.warm(scenario)

    def in_child() -> tuple[int, int]:
        before = path.compiled.cache_info().hits  # type: ignore[attr-defined]
        path.compiled(scenario)  # found, not built: the parent built it
        return len(loop.run.signatures), path.compiled.cache_info().hits - before  # type: ignore[attr-defined]

    outcome = run_isolated(in_child, 30.0)
    assert outcome.kind == "ok"
    assert outcome.value is not None
    signatures, hits = outcome.value
    assert signatures >= 1  # the kernel is loaded before the child calls it
    assert hits == 1


def test_a_scenario_is_warmed_once_per_process() -> None:
    scenario = build_scenario("four_bar[omega=34]")
    before = warm.counts["scenarios"]
    warm.warm(scenario)
    warm.warm(build_scenario("four_bar[omega=34]"))  # equal, though another object
    assert warm.counts["scenarios"] == before + 1


def crash_hang_then_good(scenario: Scenario, adapter: Adapter) -> list[Setting]:
    return [GOOD[1], Setting.of("crash"), GOOD[0], Setting.of("hang"), Setting.of("good", dt=0.1)]


def test_a_crash_and_a_hang_after_the_warm_up_cost_their_own_rows(tmp_path: Path) -> None:
    store = ResultsStore(tmp_path / "out")
    Runner(
        store, ["fake"], CONFIG, loader=fake_loader(tmp_path / "log"), truth=fake_truth, progress=False,
        settings=crash_hang_then_good,
    ).run(["four_bar"])  # fmt: skip
    frame, _ = read_results(tmp_path / "out")
    status = dict(zip(frame["setting"], frame["status"], strict=True))
    assert status == {
        "good dt=0.001": "ok", "crash": "failed", "good dt=0.01": "ok", "hang": "timeout",
        "good dt=0.1": "ok",
    }  # fmt: skip
    errors = dict(zip(frame["setting"], frame["position_length_max"], strict=True))
    for dt in (0.001, 0.01, 0.1):  # the fake's known error: x of the first body off by dt
        assert np.isclose(errors[f"good dt={dt:g}"], dt, rtol=1e-12)


COLD = """
import sys
from pathlib import Path
import reports.run.group_runs as group_runs
from reports.store.results_store import ResultsStore
from reports.run.runner import Runner, RunConfig
if sys.argv[2] == "cold":
    group_runs.warm = lambda scenario: None  # the previous path: the forked runs load the kernels
config = RunConfig(ladder=True, repeats=1, warmup=0)
Runner(ResultsStore(Path(sys.argv[1])), ["reference"], config, progress=False).run(
    ["four_bar[omega=12]", "slider_crank"]
)
from reports.run import warm
print(dict(warm.counts))
"""


def run_fresh(directory: Path, how: str) -> tuple[pd.DataFrame, str]:
    """A run in a fresh interpreter, so that the cold one starts with nothing loaded."""
    done = subprocess.run(
        [sys.executable, "-c", COLD, str(directory), how], capture_output=True, text=True, check=True
    )
    frame, _ = read_results(directory)
    return frame.sort_values(list(KEY)).reset_index(drop=True), done.stdout


def test_warm_runs_give_the_cold_path_s_rows(tmp_path: Path) -> None:
    cold, cold_counts = run_fresh(tmp_path / "cold", "cold")
    warm_rows, warm_counts = run_fresh(tmp_path / "warm", "warm")
    # warmed before the one fork: the second scenario's program is built in the kept child
    assert "'scenarios': 1" in warm_counts and "scenarios" not in cold_counts
    # 12: the ladders with MuJoCo's and Exudyn's untuned points
    assert len(cold) == 12 and set(cold["status"]) == {"ok"}
    for column in cold.columns.difference(VARIES_BETWEEN_RUNS):
        for a, b in zip(cold[column], warm_rows[column], strict=True):
            both_nan = isinstance(a, float) and isinstance(b, float) and np.isnan(a) and np.isnan(b)
            assert both_nan or json.dumps(a, default=str) == json.dumps(b, default=str), (column, a, b)
