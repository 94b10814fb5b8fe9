"""The Dask backend against one LocalCluster on the loopback address, shared by the module: the same
rows as the serial runner, a run through `--cluster`, and a worker killed mid-run costing only its
group, with a resumed run that loses and duplicates nothing."""

from __future__ import annotations

import math
from collections.abc import Iterator
from pathlib import Path

import pandas as pd
import pytest
from distributed import Client

from adapters.threads import blas_threads
from reports.cli.main import main
from reports.run.dask_backend import DaskRunner, local_cluster, warm_plugin
from reports.run.runner import RunConfig, Runner
from reports.store.results_store import KEY, ResultsStore, read_results
from tests.support.fake_engine import fake_loader, fake_truth
from tests.support.run_columns import VARIES_BETWEEN_RUNS

QUICK = RunConfig(ladder=False, repeats=1, warmup=0, timeout=120.0)
SCENARIOS = ["slider_crank", "four_bar[crank_length=0.08]"]  # the second meets a dead point
ENGINES = ["reference", "mujoco"]


@pytest.fixture(scope="module")
def cluster() -> Iterator[str]:
    with local_cluster(2) as running:
        yield running.scheduler_address


def rows(directory: Path) -> pd.DataFrame:
    frame, _ = read_results(directory)
    return frame.sort_values(list(KEY)).reset_index(drop=True)


def same_rows(serial: pd.DataFrame, parallel: pd.DataFrame) -> None:
    """Every column but the timings and where they were made, equal (errors to the last bit)."""
    assert list(serial[list(KEY)].itertuples(index=False)) == list(
        parallel[list(KEY)].itertuples(index=False)
    )
    for column in serial.columns.difference(VARIES_BETWEEN_RUNS):
        for a, b in zip(serial[column], parallel[column], strict=True):
            both_nan = isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b)
            assert both_nan or a == b, (column, a, b)


def test_the_cluster_gives_the_serial_runner_s_rows(cluster: str, tmp_path: Path) -> None:
    Runner(ResultsStore(tmp_path / "serial"), ENGINES, QUICK, progress=False).run(SCENARIOS)
    DaskRunner(ResultsStore(tmp_path / "dask"), ENGINES, QUICK, progress=False, cluster=cluster).run(
        SCENARIOS
    )
    serial, parallel = rows(tmp_path / "serial"), rows(tmp_path / "dask")
    same_rows(serial, parallel)
    assert set(parallel["status"]) == {"ok", "singular"}  # real outcomes, not all failures
    assert set(serial["workers"]) == {1} and set(parallel["workers"]) == {2}
    assert (parallel["host"] != "").all()
    truths = ResultsStore(tmp_path / "dask").trajectories
    assert {(s, e) for s, e, _ in truths if e == "truth"} == {(s, "truth") for s in SCENARIOS}


def test_each_dask_worker_holds_one_blas_thread(cluster: str) -> None:
    with Client(cluster) as client:
        client.register_plugin(warm_plugin(), name="mbxval-warm")
        found = client.run(blas_threads)
    assert len(found) == 2 and all(threads and set(threads.values()) == {1} for threads in found.values())


def test_a_killed_worker_costs_its_group_and_a_resume_redoes_only_that(cluster: str, tmp_path: Path) -> None:
    log = tmp_path / "calls.log"
    scenarios = ["slider_crank", "four_bar", "spur_gears"]

    def run() -> pd.DataFrame:
        DaskRunner(
            ResultsStore(tmp_path / "out"),
            ["killer"],
            QUICK,
            loader=fake_loader(log),
            truth=fake_truth,
            progress=False,
            cluster=cluster,
        ).run(scenarios)
        return rows(tmp_path / "out").set_index("scenario")

    first = run()
    assert log.with_suffix(".killed").exists()
    assert first.loc["four_bar", "status"] == "failed"
    assert "Dask worker running this group died" in first.loc["four_bar", "message"]
    assert (first.drop(index="four_bar")["status"] == "ok").all()
    calls = log.read_text().splitlines()
    assert sorted(c.split()[0] for c in calls) == ["slider_crank", "spur_gears"]

    second = run()  # the resume: the failed group again, nothing else
    assert list(second.index) == sorted(scenarios)  # one row each: none lost, none duplicated
    assert (second["status"] == "ok").all()
    assert log.read_text().splitlines()[len(calls) :] == ["four_bar good dt=0.001"]
    ok = second.drop(index="four_bar")
    pd.testing.assert_frame_equal(ok, first.drop(index="four_bar"))  # kept as stored


def test_run_through_the_cluster_option(
    cluster: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    args = ["run", "--out", str(tmp_path), "--quiet", "--suite", "quick", "--engine", "reference"]
    sweep = ["--scenario", "slider_crank", "--sweep", "offset=0,0.01"]
    with Client(cluster) as client:  # the worker killed by the test before is restarted by its nanny
        client.wait_for_workers(2, timeout=120)
    assert main([*args, *sweep, "--cluster", cluster]) == 0
    assert "2 runs (ok 2)" in capsys.readouterr().out
    frame = rows(tmp_path)
    assert list(frame["scenario"]) == ["slider_crank[offset=0.01]", "slider_crank[offset=0]"]
    assert list(frame["sweep"]) == ['{"offset": "0.01"}', '{"offset": "0"}']
    assert (frame["workers"] == 2).all()


def test_an_unreachable_scheduler_is_one_line_and_writes_nothing(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    args = ["run", "--out", str(tmp_path / "out"), "--quiet", "--suite", "quick", "--scenario", "spur_gears"]
    assert main([*args, "--engine", "reference", "--cluster", "tcp://127.0.0.1:9"]) == 2
    error = capsys.readouterr().err
    assert error.startswith("mbxval: error: ") and error.count("\n") == 1
    assert "tcp://127.0.0.1:9" in error
    assert not (tmp_path / "out" / "results.json").exists()


@pytest.mark.slow
def test_workers_2_gives_the_serial_rows_from_the_command_line(tmp_path: Path) -> None:
    """`--workers 2` (its own local cluster) against the serial default, on a narrow suite."""
    args = ["run", "--quiet", "--suite", "quick", "--engine", "reference", "--engine", "mujoco"]
    args += ["--scenario", "four_bar", "--sweep", "crank_length=0.05,0.08", "--sweep", "omega=10,50"]
    assert main([*args, "--out", str(tmp_path / "serial")]) == 0
    assert main([*args, "--out", str(tmp_path / "dask"), "--workers", "2"]) == 0
    same_rows(rows(tmp_path / "serial"), rows(tmp_path / "dask"))


def test_each_worker_warms_the_kernels_once(cluster: str, tmp_path: Path) -> None:
    from distributed import Client

    from reports.run import warm

    scenarios = ["four_bar[omega=21]", "four_bar[omega=22]", "slider_crank[omega=23]"]
    for out in ("first", "second"):  # a second run on the same workers warms nothing again
        DaskRunner(ResultsStore(tmp_path / out), ["reference"], QUICK, progress=False, cluster=cluster).run(
            scenarios
        )
    with Client(cluster) as client:
        counts = client.run(lambda: dict(warm.counts))
    assert len(counts) == 2
    assert all(c["kernels"] == 1 for c in counts.values()), counts
    assert sum(c["scenarios"] for c in counts.values()) >= len(scenarios)  # each where it first ran


def test_a_local_cluster_leaves_no_scratch_space_in_the_temporary_directory(
    tmp_path: Path, monkeypatch
) -> None:
    """The workers' scratch space is the cluster's own temporary directory, removed when it closes:
    nothing is left in the system's temporary directory (here a fresh one, TMPDIR)."""
    import tempfile

    system = tmp_path / "tmp"
    system.mkdir()
    monkeypatch.setenv("TMPDIR", str(system))
    monkeypatch.setattr(tempfile, "tempdir", None)  # read TMPDIR again
    with local_cluster(1) as running, Client(running) as client:
        assert client.submit(sum, [1, 2]).result() == 3
        assert next(p.name for p in system.iterdir()).startswith("mbxval-dask-")  # in use meanwhile
    assert list(system.iterdir()) == []
