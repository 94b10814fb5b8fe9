"""`mbxval run --suite stress` end to end: the suite's truth and settings hooks reach the runner,
and the reports carry the stability map. The fast test runs the native solver alone on a few
cases; the slow one runs every engine on the whole suite, as a user does."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from reports.cli.main import main
from reports.render.report_data import ReportData
from reports.render.stored_verdicts import Judgement, judgements, stress_rows
from reports.store.results_store import read_results
from reports.stress.cases import CASES

FEW = (
    "slider_crank/stress_dead_centre",
    "four_bar/stress_near_change_point",
    "slider_crank/stress_scale_1e-4",
)
VERDICTS = {
    "ok",
    "picked a branch",
    "wrong branch",
    "drifted",
    "diverged",
    "singular detected",
    "failed to converge",
    "failed",
    "timeout",
    "unsupported",
}


def judge_all(data: ReportData) -> list[Judgement]:
    """The verdicts the run stored with the stress cases' rows."""
    return judgements(stress_rows(data.frame))


def _run(out: Path, *extra: str) -> None:
    args = ["run", "--suite", "stress", "--out", str(out), "--quiet", *extra]
    assert main(args) == 0


def test_the_native_solver_through_the_stress_suite(tmp_path: Path) -> None:
    args = ["--engine", "reference"]
    for name in FEW:
        args += ["--scenario", name]
    _run(tmp_path, *args)
    found = {v.scenario: v for v in judge_all(ReportData.load(tmp_path))}
    dead = found["slider_crank/stress_dead_centre"]
    assert dead.verdict == "singular detected" and dead.time == pytest.approx(math.pi / 100, abs=1e-12)
    jump = found["four_bar/stress_near_change_point"]
    assert jump.verdict == "singular detected" and "truth goes on regular" in jump.detail
    scaled = found["slider_crank/stress_scale_1e-4"]
    assert scaled.verdict == "ok" and scaled.error < 1e-13  # against the closed form
    summary = (tmp_path / "summary.md").read_text()
    assert "## Stability map" in summary and "singular detected @0.03142 s" in summary
    assert 'id="stability-map"' in (tmp_path / "index.html").read_text()


@pytest.mark.slow
def test_the_whole_stress_suite_on_every_engine(tmp_path: Path) -> None:
    """Every case and engine gets a row and a verdict; the native solver detects each declared
    singular configuration at its closed-form time and is ok on every other case but the two
    whose truth needed a finer grid."""
    _run(tmp_path)
    frame, meta = read_results(tmp_path)
    assert meta["suite"] == "stress" and set(frame["scenario"]) == set(CASES)
    found = judge_all(ReportData.load(tmp_path))
    assert {v.verdict for v in found} <= VERDICTS
    native = {v.scenario: v for v in found if v.engine == "reference"}
    for name, case in CASES.items():
        expected = case.singular_time()
        if expected is not None:
            assert native[name].verdict == "singular detected", name
            assert native[name].time == pytest.approx(expected, abs=1e-8), name
        elif case.refine == 1:
            assert native[name].verdict == "ok" and native[name].error < 1e-12, name
