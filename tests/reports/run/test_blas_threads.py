"""One BLAS thread per worker (issue #40): a forked run's child, a solve and the runner's own process
(where the truths are solved) hold every loaded BLAS library to one thread, whatever the parent
process held, and the limit is threadpoolctl's, read back from the libraries themselves."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from threadpoolctl import threadpool_limits

import reports.entry
from adapters.threads import BLAS_THREADS, blas_threads, one_blas_thread
from reports.cli.main import solve_trajectory
from reports.run.isolation import Worker, run_isolated
from reports.run.runner import RunConfig, Runner
from reports.store.results_store import ResultsStore, read_results
from scenarios import load as load_scenario
from tests.support.fake_engine import fake_loader, fake_truth
from tests.support.sleeper import run_sleeper

MANY = 2
"""The threads a parent holds before: more than one, as OpenBLAS starts on a machine of 2 cores."""


@pytest.fixture
def many_threads():  # type: ignore[no-untyped-def]
    """This process's BLAS libraries at MANY threads for the test's length (restored after)."""
    one_blas_thread()  # loads scipy's library too, so that both are raised
    with threadpool_limits(limits=MANY, user_api="blas"):
        assert set(blas_threads().values()) == {MANY}
        yield


def test_both_blas_libraries_are_found() -> None:
    one_blas_thread()
    assert len(blas_threads()) >= 2, blas_threads()  # numpy's and scipy's OpenBLAS


def test_a_forked_workers_child_holds_one_blas_thread(many_threads: None) -> None:
    outcome = run_isolated(blas_threads, timeout=30.0)
    assert outcome.kind == "ok", outcome.message
    assert outcome.value and set(outcome.value.values()) == {1}
    with Worker(lambda _: blas_threads()) as worker:  # a kept worker's child, call after call
        for _ in range(2):
            found = worker.call(None, 30.0)
            assert found.kind == "ok" and found.value and set(found.value.values()) == {1}
    assert set(blas_threads().values()) == {MANY}  # the parent's own left as it was


def test_a_solve_holds_one_blas_thread(many_threads: None) -> None:
    scenario = load_scenario("four_bar")
    trajectory = solve_trajectory(scenario, "reference", grid=(0.1, 10, None))
    assert np.isfinite(trajectory.position).all()  # type: ignore[arg-type]
    assert set(blas_threads().values()) == {1}


def test_the_runners_process_holds_one_blas_thread(many_threads: None, tmp_path: Path) -> None:
    runner = Runner(
        ResultsStore(tmp_path / "store"),
        ["fake"],
        RunConfig(ladder=False, repeats=1, warmup=0, timeout=20.0),
        loader=fake_loader(tmp_path / "fakes.log"),
        truth=fake_truth,
        progress=False,
        suite="test",
    )
    runner.run(["slider_crank"])
    assert set(blas_threads().values()) == {1}  # where the truths were solved


def _threads_after_a_solve() -> int:
    """Threads of this process after a BLAS call (a worker's child: only its own main thread)."""
    matrix = np.eye(50) + 0.01 * np.ones((50, 50))
    np.linalg.solve(matrix, np.ones(50))
    return len(os.listdir(f"/proc/{os.getpid()}/task"))


def test_a_forked_workers_child_starts_no_blas_thread_pool() -> None:
    """OpenBLAS starts a new pool on any change of its count, whose threads spin on the CPU clock
    of the run being timed: a child whose parent holds one thread already changes nothing."""
    one_blas_thread()
    with Worker(lambda _: _threads_after_a_solve()) as worker:
        found = worker.call(None, 30.0)
    assert found.kind == "ok" and found.value == 1, found


def test_a_timed_row_spends_no_more_cpu_than_wall_time(tmp_path: Path) -> None:
    """A single-threaded worker's CPU seconds cannot exceed the wall seconds they passed in; other
    threads spinning in it (a BLAS pool started in the child) would make them exceed."""
    one_blas_thread()
    run_sleeper(tmp_path / "store", engines=("sleeper",))
    row = read_results(tmp_path / "store")[0].iloc[0]
    for part in ("build_time", "warmup_time", "repeats_time", "run_time"):
        assert row[part] <= row[f"{part}_wall"] + 2e-3, (part, row[part], row[f"{part}_wall"])


def test_the_command_line_loads_openblas_at_one_thread() -> None:
    """Set before numpy loads: no pool is started at all (adapters.threads), the constant agreeing."""
    code = (
        "import os; import reports.entry as e; e.main(['list', '--engine', 'reference']); import numpy as np;"
        "np.linalg.solve(np.eye(50), np.ones(50)); print(len(os.listdir('/proc/self/task')))"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert done.stdout.split()[-1] == "1", done.stdout
    assert str(BLAS_THREADS) == reports.entry.BLAS_THREADS
