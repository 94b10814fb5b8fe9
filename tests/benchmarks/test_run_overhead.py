"""The overhead benchmark's work is what the rows measured (issue #27): build, warm-up and timed
repeats summed from a tiny run's own rows, whose fake engine sleeps known times in its warm-up and
its timed runs; the sweep benchmark states the same work beside its wall time."""

from __future__ import annotations

from pathlib import Path

import pytest

from benchmarks.run_overhead import WORK, work, work_of
from benchmarks.sweep_speed import timing_line
from reports.store.results_store import read_results
from tests.support.sleeper import CONFIG, RUN, WARM, run_sleeper


@pytest.fixture(scope="module")
def tiny(tmp_path_factory: pytest.TempPathFactory) -> Path:
    directory = tmp_path_factory.mktemp("overhead") / "store"
    run_sleeper(directory, engines=("sleeper",))
    return directory


def test_the_work_is_the_rows_build_warm_up_and_repeats_summed(tiny: Path) -> None:
    rows, _ = read_results(tiny)
    count, compute, done = work_of(tiny)
    assert count == len(rows) == 1
    row = rows.iloc[0]
    assert done == pytest.approx(
        row["build_time_wall"] + row["warmup_time_wall"] + row["repeats_time_wall"], rel=1e-12
    )
    assert compute == pytest.approx(row["build_time"] + row["run_time"], rel=1e-12)
    slept = CONFIG.warmup * WARM + CONFIG.repeats * RUN  # the fake engine's CPU work, known
    cpu = row["build_time"] + row["warmup_time"] + row["repeats_time"]
    assert slept <= cpu < 3 * slept  # the CPU clock: what the fake spent, whatever the load
    assert done >= cpu - 1e-3  # one thread: its wall time holds at least its CPU time
    old_estimate = row["build_time"] + row["run_time"] * (row["warmup"] + row["repeats"])
    assert cpu > old_estimate  # the warm-up works 6 runs' time: the estimate missed it


def test_a_run_that_timed_nothing_counts_no_work(tiny: Path) -> None:
    rows, _ = read_results(tiny)
    rows.loc[:, list(WORK)] = float("nan")
    assert work(rows) == 0.0


def test_the_sweep_benchmark_states_the_work_beside_the_wall_time(tiny: Path) -> None:
    done = work_of(tiny)[2]
    line = timing_line("serial:", 4 * done, tiny)
    assert f"{done:8.2f} s work (1 rows)" in line and "wall/work 4.00 " in line
    assert line.endswith("[failed rows: 0, 0.00 s of the work]")
