"""Fault injection in SQLite's spirit, for the store's save and its repair: count the I/O calls
(fsync, rename, replace, symlink, mkdir, chmod, each data file's write, each copy) one of
them makes, then run it again failing the k-th call with ENOSPC or EIO, for every k. After each:
the store loads and verifies (or, for a repair, is refused in one line naming the repair, which
then succeeds), no row stored before is lost, no temporary file is left, and the error is one
line. Every k for a small store here; with a kill (SIGKILL) instead of an error under -m slow."""

from __future__ import annotations

import errno
import os
import shutil
import signal
import subprocess
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path

import pandas as pd
import pytest

from reports.store.files import GENERATIONS, StoreDamaged
from reports.store.repair import Repair
from reports.store.results_store import ResultsStore
from tests.support.store_runs import rows, stored_run

POINTS: list[tuple[object, str]] = [
    (os, "fsync"),
    (os, "rename"),
    (os, "replace"),
    (os, "symlink"),
    (os, "mkdir"),
    (os, "chmod"),
    (os, "link"),
    (pd.DataFrame, "to_parquet"),
    (Path, "write_text"),
    (shutil, "copy2"),
]


class Injected:
    """Counts the calls at POINTS and makes the `fail_at`-th one fail (raise `error`, or die)."""

    def __init__(self, fail_at: int | None, error: int = errno.ENOSPC, kill: bool = False) -> None:
        self.fail_at, self.error, self.kill, self.calls = fail_at, error, kill, 0

    @contextmanager
    def installed(self, monkeypatch: pytest.MonkeyPatch) -> Iterator[Injected]:
        for owner, name in POINTS:
            monkeypatch.setattr(owner, name, self._hook(getattr(owner, name)))
        try:
            yield self
        finally:
            monkeypatch.undo()

    def _hook(self, original: Callable[..., object]) -> Callable[..., object]:
        def hooked(*args: object, **kwargs: object) -> object:
            self.calls += 1
            if self.calls == self.fail_at:
                if self.kill:
                    os.kill(os.getpid(), signal.SIGKILL)
                raise OSError(self.error, os.strerror(self.error))
            return original(*args, **kwargs)

        return hooked


@pytest.fixture(scope="module")
def base(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return stored_run(tmp_path_factory, "faults")


def leftovers(directory: Path) -> list[str]:
    home = directory / GENERATIONS
    inside = [p.name for p in home.iterdir() if p.name.startswith("tmp-")] if home.is_dir() else []
    beside = [p.name for p in directory.iterdir() if p.name.startswith(".current.") or p.suffix == ".link"]
    return inside + beside


def generations(directory: Path) -> list[str]:
    home = directory / GENERATIONS
    return [p.name for p in home.iterdir() if p.name.startswith("g")] if home.is_dir() else []


def new_row_save(directory: Path) -> None:
    """A save that changes something: one stored row's error halved."""
    store = ResultsStore(directory)
    key = sorted(store.rows)[0]
    store.rows[key] = {**store.rows[key], "error": 0.5}
    store.save(dict(store.meta))


def count_calls(action: Callable[[], None], monkeypatch: pytest.MonkeyPatch) -> int:
    counter = Injected(None)
    with counter.installed(monkeypatch):
        action()
    return counter.calls


def assert_kept(directory: Path, before: pd.DataFrame) -> None:
    after = rows(directory)
    assert set(before.index) <= set(after.index)  # no row stored before is lost
    assert not leftovers(directory), leftovers(directory)


def copy(source: Path, target: Path) -> Path:
    shutil.copytree(source, target, symlinks=True)
    return target


def first_save(source: Path, directory: Path) -> None:
    """The first save of a store: the rows of `source` into an empty directory."""
    store, stored = ResultsStore(directory), ResultsStore(source)
    store.rows, store.trajectories = stored.rows, stored.trajectories
    store.save(dict(stored.meta))


@pytest.mark.parametrize("first", [False, True], ids=["a later save", "the first save"])
@pytest.mark.parametrize("error", [errno.ENOSPC, errno.EIO], ids=["ENOSPC", "EIO"])
def test_a_save_failing_at_any_io_call_keeps_the_store(
    base: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch, error: int, first: bool
) -> None:
    before = rows(base)
    start = (lambda out: out.mkdir()) if first else (lambda out: copy(base, out))
    save = (lambda out: first_save(base, out)) if first else new_row_save
    counted = tmp_path / "count"
    start(counted)
    total = count_calls(lambda: save(counted), monkeypatch)
    assert total >= 10
    for k in range(1, total + 1):
        out = tmp_path / f"k{k}"
        start(out)
        try:  # some failures are tolerated where they happen (mkdir of an existing folder)
            with Injected(k, error).installed(monkeypatch):
                save(out)
        except OSError as raised:
            assert "\n" not in str(raised)
        store = ResultsStore(out)  # loads and verifies: the state is understood, the checksums match
        if first and not store.rows:  # failed before its switch: no store, and nothing left of it
            assert generations(out) == [] and not leftovers(out)
            save(out)
        assert_kept(out, before)
        current = os.readlink(out / "current").split("/")[-1]
        assert set(generations(out)) <= set(generations(base)) | {current}  # none half-made
        new_row_save(out)  # and the next save works
        assert_kept(out, before)


def cp_rL(source: Path, target: Path) -> Path:
    subprocess.run(["cp", "-rL", str(source), str(target)], check=True)
    return target


def test_a_repair_failing_at_any_io_call_loses_nothing_and_can_be_run_again(
    base: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    before = rows(base)
    counted = cp_rL(base, tmp_path / "count")
    total = count_calls(lambda: Repair(counted).run() and None, monkeypatch)
    assert total >= 5
    for k in range(1, total + 1):
        out = cp_rL(base, tmp_path / f"k{k}")
        try:
            with Injected(k).installed(monkeypatch):
                Repair(out).run()
        except OSError as raised:
            assert "\n" not in str(raised)
        try:
            ResultsStore(out)
        except StoreDamaged as refused:
            assert "\n" not in str(refused) and "store repair" in str(refused)
        Repair(out).run()
        assert_kept(out, before)


def killed(action: Callable[[], object], at: int) -> bool:
    """Run `action` in a forked child killed at the `at`-th I/O call; True if it was killed."""
    pid = os.fork()
    if pid == 0:
        patch = pytest.MonkeyPatch()
        try:
            with Injected(at, kill=True).installed(patch):
                action()
        finally:
            os._exit(0)
    _, status = os.waitpid(pid, 0)
    return os.WIFSIGNALED(status)


@pytest.mark.slow
@pytest.mark.parametrize("what", ["save", "repair"])
def test_a_save_or_repair_killed_at_any_io_call_loses_nothing(
    base: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch, what: str
) -> None:
    before = rows(base)
    make = copy if what == "save" else cp_rL

    def act(directory: Path) -> None:
        if what == "save":
            new_row_save(directory)
        else:
            Repair(directory).run()

    counted = make(base, tmp_path / "count")
    total = count_calls(lambda: act(counted), monkeypatch)
    for k in range(1, total + 1):
        out = make(base, tmp_path / f"k{k}")
        assert killed(lambda out=out: act(out), k)
        try:
            ResultsStore(out)
        except StoreDamaged as refused:  # a kill mid-repair: refused, and the repair completes it
            assert what == "repair" and "store repair" in str(refused)
            Repair(out).run()
        new_row_save(out)  # a save cleans what the kill left
        assert_kept(out, before)


@pytest.mark.slow
def test_sigterm_during_a_run_keeps_the_store_and_leaves_no_temporary(tmp_path: Path) -> None:
    """A real `mbxval run`, terminated after its first save: one line, exit 143, the store loads,
    no temporary file, and a resume completes it."""
    import sys
    import time

    out = tmp_path / "out"
    run = ["run", "--out", str(out), "--scenario", "slider_crank", "--scenario", "four_bar"]
    command = [
        sys.executable,
        "-m",
        "reports.cli",
        *run,
        "--engine",
        "reference",
        "--engine",
        "mujoco",
        "--quiet",
    ]
    env = {**os.environ, "PYTHONPATH": str(Path(__file__).resolve().parents[3])}
    process = subprocess.Popen(command, env=env, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 120
    while not (out / "current").is_symlink():
        assert process.poll() is None and time.monotonic() < deadline
        time.sleep(0.01)
    process.send_signal(signal.SIGTERM)
    _, err = process.communicate(timeout=60)
    assert process.returncode == 143 and err.count("\n") == 1 and "terminated by SIGTERM" in err, err
    assert len(ResultsStore(out).rows) > 0 and not leftovers(out)
    assert subprocess.run(command, env=env, capture_output=True).returncode == 0
