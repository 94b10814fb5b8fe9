"""`mbxval run` from the command line: bad selections are one-line errors with status 2, a run
writes the documented files, and running again resumes instead of redoing stored runs."""

from __future__ import annotations

from pathlib import Path

import pytest

from reports.cli.main import main
from reports.store.results_store import read_results
from tests.support.engines import ENGINES


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["--suite", "nightly"], "unknown suite 'nightly'; known: default, quick"),
        (["--engine", "bullet"], f"unknown engine 'bullet'; known: {', '.join(ENGINES)}"),
        (["--scenario", "slider_crank/nope"], "slider_crank: unknown variant 'nope'"),
    ],
)
def test_bad_selection_is_a_one_line_error(
    args: list[str], words: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["run", "--out", str(tmp_path / "out"), "--quiet", *args]) == 2
    error = capsys.readouterr().err
    assert error.startswith("mbxval: error: ") and words in error and error.count("\n") == 1
    assert not (tmp_path / "out").exists()


def test_out_must_not_be_a_file(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    target = tmp_path / "file"
    target.write_text("keep me")
    assert main(["run", "--out", str(target), "--quiet", "--scenario", "spur_gears"]) == 2
    assert "is a file, not a directory" in capsys.readouterr().err
    assert target.read_text() == "keep me"


def test_run_then_resume(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    args = ["run", "--out", str(tmp_path), "--quiet", "--scenario", "spur_gears", "--engine", "pinocchio"]
    args += ["--suite", "quick"]
    assert main(args) == 0
    first, meta = read_results(tmp_path)
    assert "report: " in capsys.readouterr().out
    assert set(first["engine"]) == {"pinocchio"} and (first["status"] == "ok").all()
    assert meta["suite"] == "quick" and meta["engines"]["pinocchio"]
    kinematic = first[first["mode"] == "kinematic"]["measures"]
    assert len(kinematic) and kinematic.str.startswith("adapter loop on the engine's kinematics").all()
    assert main(args) == 0
    again, _ = read_results(tmp_path)
    assert list(again["recorded_at"]) == list(first["recorded_at"])  # nothing was run again
