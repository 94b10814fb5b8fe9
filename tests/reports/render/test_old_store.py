"""A results store written before the verdicts were stored renders: the page shows what was
stored, marks the verdicts, probes and closed-form times as not recorded, and never judges (no
solver, stress case or engine is imported to render it)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest

from reports.cli.main import main
from reports.render.clock import CPU, OLD_WALL
from reports.render.report import render_reports
from reports.store.columns import NOT_RECORDED, RECORDED_COLUMNS, WALL_COLUMNS
from reports.store.results_store import read_results
from tests.support.stores import write_schema_1

CASES = ("slider_crank/stress_dead_centre", "slider_crank")
DEAD_CENTRE = "singular detected @0.03142 s"  # pi / 100: the closed form's dead centre


@pytest.fixture(scope="module")
def fresh(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("fresh")
    args = ["run", "--suite", "stress", "--engine", "reference", "--out", str(out), "--quiet"]
    assert main([*args, *(a for name in CASES for a in ("--scenario", name))]) == 0
    return out


@pytest.fixture(scope="module")
def old(fresh: Path, tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The same rows as a store from before parts wrote them, without the columns added since."""
    return write_schema_1(
        tmp_path_factory.mktemp("old") / "store", fresh, without=[c.name for c in RECORDED_COLUMNS]
    )


def _section(text: str, heading: str) -> str:
    return text.split(heading, 1)[1].split("\n## ", 1)[0]


def test_the_fresh_store_holds_the_verdicts_decided_at_run_time(fresh: Path) -> None:
    frame, _ = read_results(fresh)
    row = frame[frame["scenario"] == CASES[0]].iloc[0]
    assert row["verdict"] == "singular detected" and row["case_probes"]
    assert DEAD_CENTRE in (fresh / "summary.md").read_text()


def test_an_old_store_shows_its_verdicts_as_not_recorded(old: Path, tmp_path: Path) -> None:
    assert "verdict" not in pd.read_parquet(old / "results.parquet").columns
    render_reports(old, tmp_path)
    summary = (tmp_path / "summary.md").read_text()
    table = [line for line in _section(summary, "## Stability map").splitlines() if line.startswith("|")]
    assert not any("singular detected" in line for line in table)  # not judged again
    for name in CASES:
        line = next(line for line in table if line.startswith(f"| {name} |"))
        assert line.count(NOT_RECORDED) == 3, line  # probes, closed form, the engine's verdict


def test_an_old_store_shows_the_same_scenario_tables(fresh: Path, old: Path, tmp_path: Path) -> None:
    render_reports(old, tmp_path)
    then, now = (fresh / "summary.md").read_text(), (tmp_path / "summary.md").read_text()
    for name in CASES:
        assert _section(now, f"\n## {name}\n") == _section(then, f"\n## {name}\n")


def test_rendering_imports_no_solver_engine_or_case(old: Path, tmp_path: Path) -> None:
    """Rendered in a fresh interpreter, the report loads none of what decides a verdict."""
    code = (
        "import sys, json\n"
        "from reports.render.report import render_reports\n"
        f"render_reports({str(old)!r}, {str(tmp_path)!r})\n"
        "deciders = ('reference_solver', 'adapters', 'reports.stress', 'reports.dynamics')\n"
        "print(json.dumps(sorted(m for m in sys.modules if m.startswith(deciders))))\n"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert json.loads(done.stdout.strip().splitlines()[-1]) == []


def test_a_store_from_before_cpu_time_says_its_run_times_are_wall(
    fresh: Path, old: Path, tmp_path: Path
) -> None:
    dropped = [c.name for c in (*RECORDED_COLUMNS, *WALL_COLUMNS)]
    render_reports(write_schema_1(tmp_path / "store", old, without=dropped), tmp_path / "page")
    assert f"Run times are {OLD_WALL} seconds." in (tmp_path / "page" / "summary.md").read_text()
    assert f"Run times are {CPU} seconds (" in (fresh / "summary.md").read_text()
