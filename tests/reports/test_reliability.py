"""Issue 12 replayed: every case it lists, each asserting its promise (exit code, one line, no
file, no row lost). The store cases use the fake engine (tests/support/fake_engine.py) so they stay
fast; the command-line cases call `main` in this process."""

from __future__ import annotations

import dataclasses
import json
import math
import os
import random
import subprocess
import sys
import threading
import time
from pathlib import Path

import pandas as pd
import pytest

import reports.gate as gate_face
from reports.cli import suite_commands
from reports.cli.main import main
from reports.gate import gate
from reports.store import files as store_files
from reports.store.files import StoreDamaged
from reports.store.lock import StoreBusy, WriterLock
from reports.store.results_store import RESULTS, TRAJECTORIES, ResultsStore, read_results, read_trajectories
from tests.support.fake_engine import FakeAdapter
from tests.support.store_runs import CONFIG, ROOT, SCENARIO, copy, fake_run, one_line_error, rows, stored_run
from tests.support.stores import table_files, write_schema_1


@pytest.fixture(scope="module")
def stored(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return stored_run(tmp_path_factory, "stored")


# --- one writer per store ------------------------------------------------------------------------
def test_a_second_writer_is_refused_naming_the_holder(stored: Path, tmp_path: Path, capsys) -> None:
    out = copy(stored, tmp_path / "out")
    before = rows(out)
    with WriterLock(out):
        status = main(["run", "--out", str(out), "--engine", "reference", "--scenario", SCENARIO, "--quiet"])
        assert status == 2
        one_line_error(capsys, "is being written by process", str(os.getpid()), "--wait")
        assert rows(out).equals(before)  # readers never block, and nothing changed
        assert main(["report", str(out), "--out", str(tmp_path / "page")]) == 0


def test_wait_takes_the_lock_when_the_holder_ends(tmp_path: Path) -> None:
    holder = WriterLock(tmp_path)
    holder.__enter__()
    threading.Timer(0.4, holder.__exit__, (None, None, None)).start()
    started = time.monotonic()
    with pytest.raises(StoreBusy):
        WriterLock(tmp_path).__enter__()
    with WriterLock(tmp_path, wait=True):
        assert time.monotonic() - started >= 0.3


# --- atomic, verifiable saves ---------------------------------------------------------------------
def test_a_save_killed_between_its_files_leaves_the_old_generation(
    stored: Path, tmp_path: Path, monkeypatch
) -> None:
    out = copy(stored, tmp_path / "out")
    before, trajectories = rows(out), read_trajectories(out)
    store = ResultsStore(out)
    store.rows.clear()
    real = store_files.sync_file

    def die_after_first_file(path: Path) -> None:
        real(path)
        if path.name == RESULTS:
            raise KeyboardInterrupt

    monkeypatch.setattr(store_files, "sync_file", die_after_first_file)
    with pytest.raises(KeyboardInterrupt):
        store.save({})
    monkeypatch.undo()
    assert rows(out).equals(before) and set(read_trajectories(out)) == set(trajectories)
    assert not list((out / store_files.GENERATIONS).glob("tmp-*"))  # no temporary file left


def test_a_deleted_trajectories_file_is_rebuilt_on_resume(stored: Path, tmp_path: Path) -> None:
    out = copy(stored, tmp_path / "out")
    expected = set(read_trajectories(out))
    import shutil

    shutil.rmtree((out / "current" / TRAJECTORIES).resolve())
    assert ResultsStore(out).lost_trajectories
    fake_run(out, dataclasses.replace(CONFIG, keep_failures=True))
    assert set(read_trajectories(out)) == expected
    assert len(rows(out)) == len(rows(stored))


@pytest.mark.parametrize("name", [RESULTS, TRAJECTORIES])
def test_every_bit_flip_is_detected_and_never_copied_forward(
    stored: Path, tmp_path: Path, name: str, capsys
) -> None:
    out = copy(stored, tmp_path / "out")
    target = table_files(out / "current", name)[-1]
    pristine = target.read_bytes()
    generator, detected = random.Random(5), 0
    flips = 100
    for _ in range(flips):
        data = bytearray(pristine)
        data[generator.randrange(len(data))] ^= 1 << generator.randrange(8)
        target.write_bytes(bytes(data))
        with pytest.raises(StoreDamaged, match="does not match its checksum"):
            ResultsStore(out)
        detected += 1
    assert detected == flips
    status = main(["run", "--out", str(out), "--engine", "reference", "--scenario", SCENARIO, "--quiet"])
    assert status == 2
    one_line_error(capsys, "is damaged", name, "move it aside")
    assert target.read_bytes() != pristine  # left as it is, not overwritten by a copy of itself
    assert main(["report", str(out)]) == 2
    one_line_error(capsys, "is damaged")


def test_a_store_without_its_status_column_is_refused(stored: Path, tmp_path: Path, capsys) -> None:
    """A store whose rows lack a column every store has had is refused, naming it."""
    out = write_schema_1(tmp_path / "old", stored, without=["status"])
    assert main(["report", str(out)]) == 2
    one_line_error(capsys, "lacks the columns status")


def test_a_plain_table_that_no_generation_holds_is_refused_and_kept(
    stored: Path, tmp_path: Path, capsys
) -> None:
    """A results.parquet in DIR with no generation (a layout this mbxval does not read) is neither
    read as empty nor written over: the run stops in one line naming the repair."""
    out = tmp_path / "plain"
    out.mkdir()
    frame, _ = read_results(stored)
    frame.to_parquet(out / RESULTS, index=False)
    pristine = (out / RESULTS).read_bytes()
    assert main(["report", str(out)]) == 2
    one_line_error(capsys, "not in a state mbxval understands", "mbxval store repair")
    with pytest.raises(StoreDamaged, match="no generation"):
        fake_run(out)
    assert (out / RESULTS).read_bytes() == pristine and not (out / "current").exists()


# --- resume never loses a good row ----------------------------------------------------------------
def test_an_unavailable_engine_keeps_its_rows(stored: Path, tmp_path: Path, capsys) -> None:
    out = copy(stored, tmp_path / "out")
    before = rows(out)

    def broken(name: str) -> FakeAdapter:
        raise ImportError("libfake.so: cannot open shared object file")

    fake_run(out, loader=broken)
    assert rows(out).drop(columns=["recorded_at"]).equals(before.drop(columns=["recorded_at"]))
    assert "fake is unavailable: its 3 stored rows are kept" in capsys.readouterr().err


def test_failures_are_retried_unless_kept(stored: Path, tmp_path: Path) -> None:
    out = copy(stored, tmp_path / "out")
    log = tmp_path / "calls.log"
    fake_run(out, dataclasses.replace(CONFIG, keep_failures=True))
    assert not log.exists() or "raise" not in log.read_text()
    fake_run(out)
    assert log.read_text().splitlines() == [f"{SCENARIO} raise"]  # the failed row, and only it
    assert len(rows(out)) == len(rows(stored))


def test_stale_rows_are_rerun_or_kept_marked(stored: Path, tmp_path: Path, capsys) -> None:
    out = copy(stored, tmp_path / "out")
    log = tmp_path / "calls.log"
    fake_run(out, dataclasses.replace(CONFIG, keep_failures=True, keep_stale=True), version="0.1-fake")
    after = rows(out)
    assert after["stale"].all() and not log.exists()
    assert "keeping 3 stale rows, marked stale (3 from fake 0.0-fake)" in capsys.readouterr().err
    fake_run(out, dataclasses.replace(CONFIG, keep_failures=True), version="0.1-fake")
    assert "rerunning 3 stale rows" in capsys.readouterr().err
    after = rows(out)
    assert not after["stale"].any() and set(after["engine_version"]) == {"0.1-fake"}
    assert len(after) == len(rows(stored))


def test_rows_carry_the_revision_they_were_made_under(stored: Path, tmp_path: Path) -> None:
    out = copy(stored, tmp_path / "out")
    store = ResultsStore(out)
    for row in store.rows.values():
        row["revision"] = "0" * 40
    store.save(store.meta)
    log = tmp_path / "calls.log"
    fake_run(out, dataclasses.replace(CONFIG, keep_failures=True))
    assert len(log.read_text().splitlines()) == 3  # every row made again under this revision
    assert "0" * 40 not in set(rows(out)["revision"])


# --- a gate that cannot pass by accident ----------------------------------------------------------
CELL = {"scenario": "a", "engine": "e", "setting": "s", "is_default": True, "status": "ok"}


def write_baseline(path: Path, cells: object) -> Path:
    path.write_text(json.dumps({"schema_version": 1, "cells": cells}))
    return path


@pytest.mark.parametrize(
    ("cells", "words"),
    [
        ("not a list", "'cells' must be a non-empty list"),
        ([], "'cells' must be a non-empty list"),
        ([{**CELL, "error": "1e-9"}], "'error' must be a number or null"),
        ([{**CELL, "error": None}], "an ok cell without an error"),
    ],
)  # fmt: skip
def test_an_unsound_baseline_is_bad_input(stored: Path, tmp_path: Path, cells, words: str, capsys) -> None:
    baseline = write_baseline(tmp_path / "b.json", cells)
    assert main(["check", "--baseline", str(baseline), "--results", str(stored)]) == 2
    one_line_error(capsys, words)


@pytest.mark.parametrize("factor", ["nan", "0", "-1", "inf"])
def test_a_factor_that_is_not_positive_and_finite_is_bad_input(
    stored: Path, tmp_path: Path, factor, capsys
) -> None:
    baseline = tmp_path / "b.json"
    gate.write_baseline(baseline, read_results(stored)[0], {})
    assert main(["check", "--baseline", str(baseline), "--results", str(stored), "--factor", factor]) == 2
    one_line_error(capsys, "--factor")


def test_no_cell_in_common_or_a_smaller_baseline_is_bad_input(stored: Path, tmp_path: Path, capsys) -> None:
    frame = read_results(stored)[0]
    other = frame.assign(scenario="four_bar")
    baseline = tmp_path / "b.json"
    gate.write_baseline(baseline, pd.concat([other, frame.iloc[:1]]), {})
    assert main(["check", "--baseline", str(baseline), "--results", str(stored)]) == 2
    one_line_error(capsys, "the baseline lacks 2 of the 3 cells")
    with pytest.raises(gate.GateError, match="0 cells compared"):
        gate.judge(gate.baseline_cells(other), frame.iloc[:0])


def test_every_level_is_compared_keyed_per_level() -> None:
    def cell(**errors: float) -> pd.DataFrame:
        row = {
            "scenario": "a",
            "engine": "e",
            "setting": "x",
            "is_default": True,
            "status": "ok",
            "message": "",
        }
        return pd.DataFrame([{**row, "error": errors.get("error_position", math.nan), **errors}])

    base = gate.baseline_cells(cell(error_position=1e-9, error_velocity=1e-8, error_acceleration=math.nan))
    assert gate.judge(base, cell(error_position=1e-9, error_velocity=1e-8)).passed  # a level NaN in both
    worse = gate.judge(base, cell(error_position=1e-9, error_velocity=1e-6, error_acceleration=1.0))
    assert [r.what for r in worse.regressions] == ["velocity error 1e-06 > 10 x baseline 1e-08"]
    lost = gate.judge(base, cell(error_position=1e-9))  # no velocity column: the level not produced
    assert [r.what for r in lost.regressions] == ["velocity error no longer measured (baseline 1e-08)"]


def test_update_says_what_it_adds_drops_and_changes(stored: Path, tmp_path: Path, capsys) -> None:
    frame = read_results(stored)[0]
    old = pd.concat([frame.iloc[1:], frame.iloc[:1].assign(scenario="four_bar")])
    old.loc[old.index[0], ["error", "error_position"]] = 0.5
    baseline = tmp_path / "b.json"
    gate.write_baseline(baseline, old, {})
    assert main(["check", "--baseline", str(baseline), "--results", str(stored), "--update"]) == 0
    text = capsys.readouterr().out
    assert "3 cells (was 3): 1 added, 1 dropped, 1 changed" in text
    assert "  + slider_crank x fake" in text and "  - four_bar x fake" in text and "  ~ slider_crank" in text


@pytest.mark.parametrize(
    "text",
    ["meeting notes\nnot a baseline\n", '{"cells": [1, 2]}', "[]", '{"schema_version": 99, "cells": []}'],
)
def test_update_refuses_to_overwrite_a_file_that_is_not_a_baseline(
    text: str, stored: Path, tmp_path: Path, capsys
) -> None:
    notes = tmp_path / "notes.txt"
    notes.write_text(text)
    code = main(["check", "--baseline", str(notes), "--results", str(stored), "--update"])
    assert code == 2
    one_line_error(capsys, f"--baseline {notes}", "not a baseline", "--update writes only a baseline")
    assert notes.read_text() == text
    fresh = tmp_path / "new.json"  # a new path is written, and then updated as the baseline it is
    for _ in range(2):
        assert main(["check", "--baseline", str(fresh), "--results", str(stored), "--update"]) == 0
    assert gate.read_baseline(fresh)


def test_check_runs_what_it_compares_unless_results_is_given(tmp_path: Path) -> None:
    args = suite_commands_parser(
        ["check", "--baseline", "b.json", "--out", str(tmp_path), "--scenario", SCENARIO]
    )
    assert suite_commands.select(args, tmp_path, rerun=True).config.rerun


def suite_commands_parser(argv: list[str]):  # type: ignore[no-untyped-def]
    from reports.cli.main import parser

    return parser().parse_args(argv)


# --- inputs validated where they enter ------------------------------------------------------------
BAD_INPUTS = [
    (["solve", "four_bar_chain", "--set", "loops=1e30"], "loops"),
    (["solve", SCENARIO, "--steps", "1000000000"], "GiB"),
    (["solve", SCENARIO, "--steps", "50000000"], "GiB"),
    (["solve", SCENARIO, "--set", "crank_length=1e308"], "crank_length"),
    (["solve", SCENARIO, "--set", "steps=inf"], "steps"),
    (["solve", "four_bar", "--set", "branch=inf"], "branch"),
    (["solve", "cam_roller", "--set", "profile=spline", "--set", "knots=1e30"], "knots"),
    (["solve", SCENARIO, "--dt", "1e-15"], "GiB"),
    (["solve", SCENARIO, "--t-end", "1e300"], "--t-end"),
    (["solve", SCENARIO, "--setting", "nosuch=1"], "reference: unknown option 'nosuch'; known: tolerance"),
    (["solve", SCENARIO, "--engine", "pinocchio", "--setting", "tol=-1"], "tol"),
    (["solve", SCENARIO, "--engine", "pinocchio", "--setting", "tol=nan"], "tol"),
    (["solve", SCENARIO, "--engine", "pinocchio", "--setting", "nosuch=1"], "known:"),
    (["solve", SCENARIO, "--engine", "mujoco", "--setting", "tc=0"], "tc"),
    (["solve", SCENARIO, "--engine", "mujoco", "--setting", "impedance=2"], "impedance"),
    (["solve", SCENARIO, "--engine", "mujoco", "--setting", "dt=0"], "dt"),
    (["solve", SCENARIO, "--engine", "mujoco", "--setting", "nosuch=1"], "known:"),
    (["export", SCENARIO, "--setting", "dt=nan"], "dt"),
    (["export", SCENARIO, "--setting", "dt=0"], "dt"),
    (["export", SCENARIO, "--setting", "dt=abc"], "dt"),
    (["export", SCENARIO, "--setting", "nosuch=1"], "known:"),
    (["export", SCENARIO, "--mode", "nosuch"], "mujoco: unknown mode 'nosuch'; known:"),
]


@pytest.mark.parametrize(("argv", "words"), BAD_INPUTS, ids=[" ".join(a[2:]) for a, _ in BAD_INPUTS])
def test_bad_input_is_one_line_exit_2_and_no_file(
    argv: list[str], words: str, tmp_path: Path, capsys
) -> None:
    out = tmp_path / "out.file"
    assert main([*argv, "--out", str(out)]) == 2
    one_line_error(capsys, words)
    assert not out.exists() and not list(tmp_path.iterdir())


RUN_OPTIONS = [
    (["--timeout", "nan"], "--timeout"),
    (["--timeout", "0"], "--timeout"),
    (["--timeout", "-1"], "--timeout"),
    (["--repeats", "-3"], "--repeats"),
    (["--warmup", "-2"], "--warmup"),
]


@pytest.mark.parametrize(("options", "words"), RUN_OPTIONS)
def test_bad_run_options_are_refused_before_anything_is_written(
    options, words, tmp_path: Path, capsys
) -> None:
    out = tmp_path / "out"
    assert main(["run", "--out", str(out), "--scenario", SCENARIO, "--engine", "reference", *options]) == 2
    one_line_error(capsys, words)
    assert not out.exists()


def test_report_into_an_existing_file_is_refused(stored: Path, tmp_path: Path, capsys) -> None:
    existing = tmp_path / "existing.csv"
    existing.write_text("mine\n")
    assert main(["report", str(stored), "--out", str(existing)]) == 2
    one_line_error(capsys, "is a file")
    assert existing.read_text() == "mine\n"


# --- Ctrl-C and closed pipes ----------------------------------------------------------------------
def interrupt(*args: object, **kwargs: object) -> None:
    raise KeyboardInterrupt


def test_ctrl_c_while_writing_a_csv_leaves_no_file(tmp_path: Path, monkeypatch, capsys) -> None:
    from scenarios.trajectory import Trajectory

    monkeypatch.setattr(Trajectory, "write_csv", interrupt)
    assert main(["solve", SCENARIO, "--steps", "10", "--out", str(tmp_path / "t.csv")]) == 130
    err = capsys.readouterr().err
    assert err.startswith("mbxval: interrupted") and err.count("\n") == 1
    assert not list(tmp_path.iterdir())


@pytest.mark.parametrize("command", ["report", "check"])
def test_ctrl_c_in_report_or_check_is_one_line(
    stored: Path, tmp_path: Path, command: str, monkeypatch, capsys
) -> None:
    monkeypatch.setattr(suite_commands, "render_reports", interrupt)
    monkeypatch.setattr(gate_face, "judge", interrupt)  # the command reads the gate's face
    baseline = tmp_path / "b.json"
    gate.write_baseline(baseline, read_results(stored)[0], {})
    argv = (
        ["report", str(stored)]
        if command == "report"
        else ["check", "--baseline", str(baseline), "--results", str(stored)]
    )
    assert main(argv) == 130
    err = capsys.readouterr().err
    assert err.startswith("mbxval: interrupted") and err.count("\n") == 1


def test_ctrl_c_in_the_final_render_of_run_is_one_line(tmp_path: Path, monkeypatch, capsys) -> None:
    monkeypatch.setattr(suite_commands, "run_selection", lambda *a, **k: None)
    monkeypatch.setattr(suite_commands, "render_reports", interrupt)
    assert (
        main(["run", "--out", str(tmp_path / "out"), "--scenario", SCENARIO, "--engine", "reference"]) == 130
    )
    err = capsys.readouterr().err
    assert err.startswith("mbxval: interrupted") and err.count("\n") == 1


def test_a_closed_pipe_ends_quietly() -> None:
    # 20000 rows, about 3 MB: far past a pipe's 64 kB buffer, so the writer meets the closed end
    command = f"{sys.executable} -m reports.cli solve {SCENARIO} --steps 20000 | head -n 1"
    done = subprocess.run(
        ["bash", "-o", "pipefail", "-c", command],
        capture_output=True,
        text=True,
        cwd=ROOT,
        env={**os.environ, "PYTHONPATH": str(ROOT)},
        timeout=300,
    )
    assert done.stdout.count("\n") == 1 and done.stderr == ""
    assert done.returncode == 141


# --- the native solver without a writable numba cache ----------------------------------------------
def test_the_native_solver_runs_without_a_writable_cache(tmp_path: Path) -> None:
    script = tmp_path / "nocache.py"
    script.write_text(
        "import numba.core.caching as caching\n"
        "def refuse(self):\n    raise OSError('read-only file system')\n"
        "caching._CacheLocator.ensure_cache_path = refuse\n"
        "import numpy as np, adapters, scenarios\n"
        "s = scenarios.build('slider_crank')\n"
        "a = adapters.load('reference')\n"
        "r = a.run(s, a.default_setting(s), np.asarray(s.times()))\n"
        "print(r.status, np.isfinite(r.trajectory.position).all(), ' | '.join(r.warnings))\n"
    )
    done = subprocess.run(
        [sys.executable, str(script)],
        capture_output=True,
        text=True,
        cwd=ROOT,
        env={**os.environ, "PYTHONPATH": str(ROOT)},
        timeout=300,
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith("ok True") and "the plain path runs" in done.stdout


def test_ctrl_c_while_the_command_line_loads_is_one_line() -> None:
    import signal

    # The Ctrl-C arrives as the command line starts to load (a finder ahead of Python's own sends
    # it when reports.cli.main is first looked for): on an idle machine a timed signal can come
    # after the whole solve has finished.
    code = (
        "import os, signal, sys\n"
        "class CtrlC:\n"
        "    def find_spec(self, name, path=None, target=None):\n"
        "        if name == 'reports.cli.main':\n"
        "            os.kill(os.getpid(), signal.SIGINT)\n"
        "sys.meta_path.insert(0, CtrlC())\n"
        "from reports.entry import main\n"
        "sys.exit(main(['solve', 'slider_crank']))\n"
    )
    child = subprocess.Popen(
        [sys.executable, "-c", code],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        cwd=ROOT,
        env={**os.environ, "PYTHONPATH": str(ROOT)},
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),  # as in a terminal
    )
    out, err = child.communicate(timeout=120)
    assert (child.returncode, err, out) == (130, "mbxval: interrupted while starting\n", "")
