"""Issue 22: outputs are regular files, written whole or not at all. `--out` onto a FIFO, a
device or a directory is refused in one line, exit 2, the target untouched; a symbolic link is
written through (the link stays, its target is replaced); modes follow the umask (an existing
file keeps its own); a failing write (ENOSPC at fsync) leaves the old file as it was and no
temporary file; SIGTERM during a write ends with one line, exit 143, and no temporary file."""

from __future__ import annotations

import errno
import os
import signal
import stat
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from reports.cli.main import main
from reports.gate import gate
from reports.render.report import render_reports
from reports.store.atomic_write import write_text
from reports.store.results_store import read_results
from tests.support.store_runs import ROOT, SCENARIO, one_line_error, stored_run

COMMANDS = {
    "solve": ["solve", SCENARIO, "--steps", "10", "--out"],
    "export toml": ["export", SCENARIO, "--format", "toml", "--out"],
    "export mujoco": ["export", SCENARIO, "--engine", "mujoco", "--out"],
    "check --update": ["check", "--results", "{stored}", "--update", "--baseline"],
}


@pytest.fixture
def umask() -> Iterator[None]:
    before = os.umask(0o022)
    yield
    os.umask(before)


def argv(command: str, out: Path, stored: Path) -> list[str]:
    return [a.replace("{stored}", str(stored)) for a in COMMANDS[command]] + [str(out)]


def old_text(command: str, stored: Path, folder: Path) -> str:
    """What an existing output holds before the command replaces it: for `check --update` a
    baseline (of all but one stored cell: it refuses to overwrite a file that is not one)."""
    if command != "check --update":
        return "old\n"
    made = folder / "made-old-baseline"
    frame, meta = read_results(stored)
    gate.write_baseline(made, frame.iloc[1:], meta)
    text = made.read_text()
    made.unlink()
    return text


@pytest.fixture(scope="module")
def stored(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return stored_run(tmp_path_factory, "stored")


@pytest.mark.parametrize("command", COMMANDS)
@pytest.mark.parametrize("kind", ["FIFO", "device", "directory"])
def test_an_output_that_is_not_a_regular_file_is_refused_untouched(
    tmp_path: Path, stored: Path, command: str, kind: str, capsys: pytest.CaptureFixture[str]
) -> None:
    target = tmp_path / "target"
    if kind == "FIFO":
        os.mkfifo(target)
    elif kind == "directory":
        target.mkdir()
    else:
        target = Path(os.devnull)
    before = os.stat(target)
    assert main(argv(command, target, stored)) == 2
    one_line_error(capsys, str(target), {"FIFO": "a FIFO", "device": "character device"}.get(kind, kind))
    after = os.stat(target)
    assert (after.st_mode, after.st_ino, after.st_mtime_ns) == (
        before.st_mode,
        before.st_ino,
        before.st_mtime_ns,
    )
    assert sorted(p.name for p in tmp_path.iterdir()) == (["target"] if kind != "device" else [])


@pytest.mark.parametrize("command", COMMANDS)
def test_a_symlink_is_written_through(tmp_path: Path, stored: Path, command: str, umask: None) -> None:
    real, link = tmp_path / "real", tmp_path / "link"
    old = old_text(command, stored, tmp_path)
    real.write_text(old)
    link.symlink_to(real.name)
    assert main(argv(command, link, stored)) == 0
    assert link.is_symlink() and os.readlink(link) == real.name
    assert real.read_text() != old and len(real.read_text()) > 100
    assert sorted(p.name for p in tmp_path.iterdir()) == ["link", "real"]


@pytest.mark.parametrize("mask", [0o022, 0o077])
@pytest.mark.parametrize("command", COMMANDS)
def test_modes_follow_the_umask_and_an_existing_file_keeps_its_own(
    tmp_path: Path, stored: Path, command: str, mask: int, umask: None
) -> None:
    new, existing = tmp_path / "new", tmp_path / "existing"
    existing.write_text(old_text(command, stored, tmp_path))
    existing.chmod(0o640)
    os.umask(mask)
    assert main(argv(command, new, stored)) == 0
    assert main(argv(command, existing, stored)) == 0
    assert stat.S_IMODE(new.stat().st_mode) == 0o666 & ~mask
    assert stat.S_IMODE(existing.stat().st_mode) == 0o640


def test_the_report_pages_follow_the_umask(tmp_path: Path, stored: Path, umask: None) -> None:
    os.umask(0o077)
    page = render_reports(stored, tmp_path / "page")
    assert stat.S_IMODE(page.stat().st_mode) == 0o600


def full_disk(*args: object) -> None:
    raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))


@pytest.mark.parametrize("command", COMMANDS)
def test_a_full_disk_leaves_the_old_file_and_no_temporary(
    tmp_path: Path, stored: Path, command: str, monkeypatch: pytest.MonkeyPatch, capsys
) -> None:
    old, text = tmp_path / "old", old_text(command, stored, tmp_path)
    old.write_text(text)
    monkeypatch.setattr(os, "fsync", full_disk)
    assert main(argv(command, old, stored)) == 2
    one_line_error(capsys, "No space left on device")
    assert old.read_text() == text
    assert [p.name for p in tmp_path.iterdir()] == ["old"]


def test_a_full_disk_while_writing_the_report_or_the_baseline_keeps_the_old(
    tmp_path: Path, stored: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    page = render_reports(stored, tmp_path)
    before = page.read_bytes()
    baseline = tmp_path / "baseline.json"
    frame, meta = read_results(stored)
    gate.write_baseline(baseline, frame, meta)
    kept = baseline.read_bytes()
    monkeypatch.setattr(os, "fsync", full_disk)
    with pytest.raises(OSError, match="No space"):
        render_reports(stored, tmp_path)
    with pytest.raises(OSError, match="No space"):
        gate.write_baseline(baseline, frame.iloc[:1], meta)
    assert page.read_bytes() == before and baseline.read_bytes() == kept
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".")]


def test_sigterm_while_writing_leaves_no_temporary_file(tmp_path: Path) -> None:
    """A real process, terminated while its CSV's temporary file is being written."""
    out = tmp_path / "t.csv"
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    command = [
        sys.executable,
        "-m",
        "reports.cli",
        "solve",
        "four_bar",
        "--steps",
        "20000",
        "--out",
        str(out),
    ]
    process = subprocess.Popen(command, cwd=tmp_path, env=env, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 60
    while not any(p.name.startswith(".t.csv") for p in tmp_path.iterdir()):
        assert process.poll() is None and time.monotonic() < deadline, "the temporary file never appeared"
        time.sleep(0.01)
    process.send_signal(signal.SIGTERM)
    _, err = process.communicate(timeout=60)
    assert process.returncode == 143
    assert err.startswith("mbxval: terminated by SIGTERM") and err.count("\n") == 1, err
    assert list(tmp_path.iterdir()) == []


def test_a_write_removes_the_temporary_files_killed_writers_left(tmp_path: Path) -> None:
    """What a kill -9 leaves (`.index.html.<pid>.<hex>.tmp`) is removed by the next write to the
    folder once it is a minute old and its writer is gone; a live writer's, a young one and files
    of other names are kept."""
    ended = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True)
    dead = int(ended.stdout)
    old = time.time() - 120
    names = {
        f".index.html.{dead}.0123abcd.tmp": False,  # a killed writer's, old: removed
        ".big.csv.89abcdef.tmp": False,  # the naming without a pid, old: removed
        f".big.csv.{os.getpid()}.0123abcd.tmp": True,  # a live writer's (this process): kept
        f".summary.md.{dead}.fedcba98.tmp": True,  # young: kept
        ".notes.tmp": True,  # not our naming: kept
        "data.0123abcd.tmp": True,  # not hidden, not ours: kept
    }
    for name in names:
        (tmp_path / name).write_text("partial")
        if not name.startswith(".summary"):
            os.utime(tmp_path / name, (old, old))
    write_text(tmp_path / "index.html", "<p>new</p>")
    left = {p.name for p in tmp_path.iterdir()} - {"index.html"}
    assert left == {name for name, kept in names.items() if kept}
