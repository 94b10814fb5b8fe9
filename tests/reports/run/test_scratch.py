"""Scratch directories a kill -9 leaves in the system's temporary directory are removed by the next
run of their kind, and only those: a live run's scratch (its lock held), a directory of another
name, and one whose maker is alive but has not locked it yet are kept. Checked with real processes:
a local Dask cluster on 127.0.0.1 in a child killed with SIGKILL, then a new cluster."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import tempfile
from collections.abc import Iterator
from pathlib import Path

import pytest

from reports.run import scratch
from reports.run.dask_backend import local_cluster

ROOT = Path(__file__).resolve().parents[3]

HOLD = """
import sys, time
from reports.run.{module} import {function}
with {function}({argument}) as made:
    print(getattr(made, "scheduler_address", made), flush=True)
    time.sleep(600)
"""


@pytest.fixture
def system_tmp(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A fresh system temporary directory (TMPDIR), for this process and its children."""
    system = tmp_path / "tmp"
    system.mkdir()
    monkeypatch.setenv("TMPDIR", str(system))
    monkeypatch.setattr(tempfile, "tempdir", None)  # read TMPDIR again
    return system


def _holder(module: str, function: str, argument: str) -> Iterator[tuple[subprocess.Popen[str], str]]:
    """A child process inside `function(argument)`, in its own process group; the line it printed."""
    code = HOLD.format(module=module, function=function, argument=argument)
    child = subprocess.Popen(
        [sys.executable, "-c", code],
        stdout=subprocess.PIPE,
        text=True,
        env={**os.environ, "PYTHONPATH": str(ROOT)},
        start_new_session=True,  # the cluster's worker processes with it, killed together
    )
    try:
        assert child.stdout is not None
        yield child, child.stdout.readline().strip()
    finally:
        os.killpg(child.pid, signal.SIGKILL)
        child.wait()


def _entries(system: Path) -> set[str]:
    return {p.name for p in system.iterdir()}


def test_a_killed_cluster_s_scratch_is_swept_by_the_next_cluster(system_tmp: Path) -> None:
    holder = _holder("dask_backend", "local_cluster", "1")
    child, address = next(holder)
    assert address.startswith("tcp://127.0.0.1:")
    left = _entries(system_tmp)
    assert len(left) == 1 and next(iter(left)).startswith(f"mbxval-dask-{child.pid}-")
    with pytest.raises(StopIteration):
        next(holder)  # kill -9 of the whole process group, as a closed terminal or the OOM killer
    assert _entries(system_tmp) == left  # nothing removed it
    with local_cluster(1):
        now = _entries(system_tmp)
        assert len(now) == 1 and not now & left  # the new cluster's own, the old one swept
    assert _entries(system_tmp) == set()


def test_a_live_run_s_scratch_is_kept(system_tmp: Path) -> None:
    holder = _holder("scratch", "scratch", "'dask'")
    _, live = next(holder)
    with scratch.scratch("dask") as mine:
        assert Path(live).is_dir() and Path(mine).is_dir()
        assert scratch.sweep("dask") == []  # both locked
    assert _entries(system_tmp) == {Path(live).name}
    next(holder, None)
    assert scratch.sweep("dask") == [Path(live).name]


def test_the_sweep_takes_only_what_it_made(system_tmp: Path) -> None:
    """A directory named like a scratch of a live process that has not locked it yet, a file, a
    link, another kind's and an unrelated name are all kept; an unlocked one of a dead process goes."""
    dead = subprocess.run(
        [sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True, text=True
    )
    gone = int(dead.stdout)
    kept = {
        f"mbxval-dask-{os.getpid()}-abc123": "dir",  # alive, between mkdtemp and its lock
        f"mbxval-dask-{gone}-file": "file",
        f"mbxval-dask-{gone}-link": "link",
        f"mbxval-check-{gone}-other": "dir",
        "mbxval-dask-notapid": "dir",
        "someone-elses": "dir",
    }
    target = system_tmp.parent / "target"
    target.mkdir()
    for name, kind in kept.items():
        path = system_tmp / name
        if kind == "dir":
            path.mkdir()
        elif kind == "file":
            path.write_text("")
        else:
            path.symlink_to(target)
    swept = system_tmp / f"mbxval-dask-{gone}-xyz789"
    swept.mkdir()
    (swept / scratch.OWNER).write_text("")
    (swept / "spill").mkdir()
    abandoned = system_tmp / f"mbxval-dask-{gone}-nolock"
    abandoned.mkdir()
    assert sorted(scratch.sweep("dask")) == sorted([swept.name, abandoned.name])
    assert _entries(system_tmp) == set(kept) and target.is_dir()
