"""Fault injection: a run killed at random points (between runs, between the files of a save,
between a generation's rename and its switch) and then resumed ends with the store an
uninterrupted run makes: the same rows, statuses and errors, every default run's trajectory, a
verified store and no leftover temporary file."""

from __future__ import annotations

import os
import random
import signal
from pathlib import Path

import pytest

from adapters.base import Setting
from reports.run.runner import RunConfig, Runner
from reports.store import files as store_files
from reports.store.results_store import ResultsStore, read_results, read_trajectories
from tests.support.fake_engine import GOOD, FakeAdapter, fake_truth

SCENARIOS = ["slider_crank", "four_bar"]
CONFIG = RunConfig(repeats=1, warmup=0, timeout=10.0, save_interval=0.0)  # a save per group
KILLS = 20
COMPARED = ("status", "error", "is_default", "mode")


class QuickFake(FakeAdapter):
    """The fake engine without its slow modes: two good settings and one that raises."""

    def ladder(self, scenario):  # type: ignore[no-untyped-def]
        return [*GOOD, Setting.of("raise")]


def run(directory: Path) -> None:
    log = directory.parent / f"{directory.name}.log"
    runner = Runner(
        ResultsStore(directory),
        ["fake"],
        CONFIG,
        loader=lambda name: QuickFake(log),
        truth=fake_truth,
        progress=False,
    )
    runner.run(SCENARIOS)


def checkpoints() -> list[tuple[object, str]]:
    """Every point where a kill is injected: each file written and synced, each rename, each row."""
    return [(store_files, "sync_file"), (os, "rename"), (os, "replace"), (ResultsStore, "add")]


def killed_run(directory: Path, after: int) -> int:
    """Run in a forked child that kills itself (SIGKILL) at the `after`-th checkpoint; returns
    how many checkpoints the child passed (all of them when it ended by itself)."""
    reader, writer = os.pipe()
    pid = os.fork()
    if pid == 0:  # the child: count checkpoints, die at the chosen one
        os.close(reader)
        passed = [0]
        for owner, name in checkpoints():
            original = getattr(owner, name)

            def hooked(*args, __original=original, **kwargs):  # type: ignore[no-untyped-def]
                passed[0] += 1
                if passed[0] == after:
                    os.kill(os.getpid(), signal.SIGKILL)
                return __original(*args, **kwargs)

            setattr(owner, name, hooked)
        try:
            run(directory)
        finally:
            os.write(writer, str(passed[0]).encode())
            os._exit(0)
    os.close(writer)
    _, status = os.waitpid(pid, 0)
    text = os.read(reader, 64).decode()
    os.close(reader)
    return int(text) if text else -1 if os.WIFSIGNALED(status) else 0


def snapshot(
    directory: Path,
) -> tuple[dict[tuple[str, str, str], tuple[object, ...]], set[tuple[str, str, str]]]:
    frame, _ = read_results(directory)
    rows = {
        (r["scenario"], r["engine"], r["setting"]): tuple(
            None if r[c] != r[c] else r[c] for c in COMPARED
        )  # NaN
        for r in frame.to_dict("records")
    }
    return rows, set(read_trajectories(directory))


def leftovers(directory: Path) -> list[str]:
    names = [p.name for p in (directory / store_files.GENERATIONS).iterdir()] if directory.exists() else []
    return [n for n in names if n.startswith("tmp-")] + [p.name for p in directory.glob(".*.link")]


@pytest.mark.slow
def test_kills_at_random_points_then_resume_equal_an_uninterrupted_run(tmp_path: Path) -> None:
    reference = tmp_path / "uninterrupted"
    total = killed_run(reference, after=0)  # after=0: never killed; counts the checkpoints
    assert total > KILLS
    expected = snapshot(reference)
    chosen = sorted(random.Random(12).sample(range(1, total + 1), KILLS))
    outcomes = []
    for number, after in enumerate(chosen):
        directory = tmp_path / f"killed{number}"
        assert killed_run(directory, after) == -1  # it did die there
        run(directory)  # the resume, uninterrupted
        outcomes.append((after, snapshot(directory) == expected, leftovers(directory)))
    failed = [o for o in outcomes if not o[1] or o[2]]
    assert not failed, failed
    assert len(outcomes) == KILLS
