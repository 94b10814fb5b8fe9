"""`mbxval check --junit/--json`: the verdict as files CI systems read, parsed by a JUnit parser;
and the shipped baselines, found by name from any directory."""

from __future__ import annotations

import json
from pathlib import Path

import junitparser
import pandas as pd
import pytest

from reports.cli.main import main
from reports.gate import baselines
from reports.store.results_store import read_results
from tests.support.stores import doctor

NARROW = ["--suite", "quick", "--scenario", "four_bar", "--engine", "reference", "--quiet"]


@pytest.fixture(scope="module")
def stored(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A narrow quick run: four_bar on the native solver, each of its settings."""
    out = tmp_path_factory.mktemp("gate-files")
    assert main(["run", "--out", str(out), "--repeats", "1", "--warmup", "0", *NARROW]) == 0
    return out


def test_the_shipped_baselines_are_found_by_name_anywhere(
    stored: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys
) -> None:
    assert {"default", "dynamics"} <= set(baselines.names())
    monkeypatch.chdir(tmp_path)  # no baselines/ here: the package's own are used
    assert main(["check", "--baseline", "default", "--results", str(stored)]) == 0
    out = capsys.readouterr().out
    assert str(baselines.SHIPPED / "default.json") in out and "no regressions" in out


def test_junit_and_json_carry_every_cell_and_each_regression(stored: Path, tmp_path: Path) -> None:
    frame, _ = read_results(stored)
    default = frame.index[frame["is_default"]][0]

    def worsen(rows: pd.DataFrame) -> None:
        rows.loc[default, ["error", "error_position"]] = 1e-3  # the baseline's is near round-off

    copy = doctor(stored, tmp_path / "doctored", worsen)
    junit, verdict = tmp_path / "check.xml", tmp_path / "check.json"
    argv = ["check", "--baseline", "default", "--results", str(copy), "--junit", str(junit)]
    assert main([*argv, "--json", str(verdict)]) == 1

    cases = [case for suite in junitparser.JUnitXml.fromfile(str(junit)) for case in suite]
    assert len(cases) == len(frame)  # one test case per compared cell
    assert {c.classname for c in cases} == {"four_bar"}
    failed = [c for c in cases if not c.is_passed]
    assert [c.name for c in failed] == ["reference [(default)]"]
    (failure,) = failed[0].result
    assert isinstance(failure, junitparser.Failure)
    assert failure.message.startswith("position error 0.001 > 10 x baseline")
    assert "allowed: 10 x the baseline's error" in failure.text
    assert all(c.system_out.startswith("status ok (baseline ok)") for c in cases if c.is_passed)

    document = json.loads(verdict.read_text())
    assert (document["passed"], document["compared"], document["regressions"]) == (False, len(frame), 1)
    (bad,) = [c for c in document["cells"] if not c["passed"]]
    position = bad["errors"]["position"]
    assert position["error"] == 1e-3 and position["growth"] == pytest.approx(
        1e-3 / max(position["baseline"], 1e-12)
    )


def test_junit_with_update_is_one_error_line(stored: Path, tmp_path: Path, capsys) -> None:
    argv = ["check", "--baseline", str(tmp_path / "b.json"), "--results", str(stored), "--update"]
    assert main([*argv, "--junit", str(tmp_path / "j.xml")]) == 2
    assert capsys.readouterr().err.startswith("mbxval: error: --junit and --json write a comparison")
    assert not (tmp_path / "j.xml").exists() and not (tmp_path / "b.json").exists()


@pytest.mark.parametrize("where", ["a directory", "a missing directory"])
def test_a_junit_file_that_cannot_be_written_is_refused_before_running(tmp_path: Path, capsys, where) -> None:
    target = tmp_path if where == "a directory" else tmp_path / "missing" / "check.xml"
    argv = ["check", "--baseline", "default", "--junit", str(target), "--out", str(tmp_path / "run"), *NARROW]
    assert main(argv) == 2
    assert capsys.readouterr().err.startswith(f"mbxval: error: --junit {target}: not a file")
    assert not (tmp_path / "run").exists()
