"""The gate against a baseline written by hand, with exactly known regressions: a results table made
by hand (one cell 10x worse, one 2x worse within the factor, one improved, one default row missing,
one failed run, and separately one new cell), and the verdict, the growth factors and the exit
status of `mbxval check` asserted cell by cell. Nothing here is taken from the gate's own output."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import pytest

from reports.cli.main import main
from reports.gate import gate
from reports.store.columns import DECLARED
from reports.store.results_store import SCHEMA_VERSION, ResultsStore

DEFAULT = "(default)"
SWEEP = "GA3 dt=0.0001"

# (scenario, engine, setting, status, position, velocity, acceleration) of the baseline
BASELINE = [
    ("slider_crank", "mujoco", "RK4 dt=0.001", "ok", 1e-6, 2e-5, 3e-4),  # becomes 10x worse
    ("slider_crank", "exudyn", "GA3 dt=0.001", "ok", 1e-6, 1e-5, 1e-4),  # 2x worse: within 3x
    ("four_bar", "mujoco", "RK4 dt=0.001", "ok", 1e-4, 1e-3, 1e-2),  # improves 1000x
    ("four_bar", "exudyn", "GA3 dt=0.001", "ok", 1e-6, 1e-5, 1e-4),  # its default row goes missing
    ("four_bar", "exudyn", SWEEP, "ok", 1e-9, 1e-8, 1e-7),  # unchanged: the pair is covered
    ("cam_roller", "mujoco", "RK4 dt=0.001", "ok", 1e-8, 1e-7, 1e-6),  # the run fails
]
FACTOR = 3.0


def baseline_text() -> str:
    """The baseline file as `mbxval check --update` writes it (reports.gate.gate.write_baseline):
    a schema version, what it was made from, and one cell per line."""
    cells = []
    for scenario, engine, setting, status, *errors in BASELINE:
        cell: dict[str, Any] = {
            "scenario": scenario,
            "engine": engine,
            "setting": setting,
            "is_default": setting != SWEEP,
            "status": status,
            "message": "",
            "error": errors[0],
        }
        cell |= {f"error_{level}": e for level, e in zip(gate.LEVELS, errors, strict=True)}
        cells.append(json.dumps(cell))
    return (
        f'{{"schema_version": {SCHEMA_VERSION}, "made_from": {{"suite": "quick"}},\n "cells": [\n'
        + ",\n".join(cells)
        + "\n ]\n}\n"
    )


def row(scenario: str, engine: str, setting: str, status: str, *errors: float, message: str = "") -> dict:
    """A results row: every declared column at its empty value, then the cell's own."""
    values = {c.name: c.empty for c in DECLARED}
    values |= {"scenario": scenario, "engine": engine, "setting": setting, "status": status}
    values |= {"is_default": setting != SWEEP, "message": message, "mode": setting.split(" ")[0]}
    if errors:
        values |= {"error": errors[0]} | {f"error_{lv}": e for lv, e in zip(gate.LEVELS, errors, strict=True)}
    return values


CURRENT = [
    row("slider_crank", "mujoco", "RK4 dt=0.001", "ok", 1e-5, 2e-5, 3e-4),  # position 10x
    row("slider_crank", "exudyn", "GA3 dt=0.001", "ok", 2e-6, 2e-5, 2e-4),  # every level 2x
    row("four_bar", "mujoco", "RK4 dt=0.001", "ok", 1e-7, 1e-6, 1e-5),  # every level / 1000
    row("four_bar", "exudyn", SWEEP, "ok", 1e-9, 1e-8, 1e-7),  # the default row is missing
    row("cam_roller", "mujoco", "RK4 dt=0.001", "diverged", message="state exploded at t = 0.2"),
]
NEW = row("spur_gears", "mujoco", "RK4 dt=0.001", "ok", 1e-9, 1e-9, 1e-9)


def store(directory: Path, rows: list[dict]) -> Path:
    results = ResultsStore(directory, fresh=True)
    for values in rows:
        results.add(values)
    results.save({"suite": "quick"})
    return directory


@pytest.fixture
def files(tmp_path: Path) -> tuple[Path, Path]:
    baseline = tmp_path / "baseline.json"
    baseline.write_text(baseline_text())
    return baseline, store(tmp_path / "results", CURRENT)


def check(capsys: pytest.CaptureFixture[str], baseline: Path, results: Path, *extra: str) -> tuple[int, str]:
    status = main(["check", "--baseline", str(baseline), "--results", str(results), *extra])
    return status, capsys.readouterr().out


def test_the_verdict_and_factors_cell_by_cell(files, tmp_path: Path, capsys) -> None:  # type: ignore[no-untyped-def]
    baseline, results = files
    verdict_file = tmp_path / "verdict.json"
    status, text = check(capsys, baseline, results, "--factor", "3", "--json", str(verdict_file))
    assert status == 1
    assert "5 cells compared, 3 regressions:" in text
    lines = [line.strip() for line in text.splitlines()[1:]]
    assert lines == [
        "- slider_crank x mujoco [(default)]: position error 1e-05 > 3 x baseline 1e-06",
        "- four_bar x exudyn [(default)]: missing: no default-setting row (baseline: ok)",
        "- cam_roller x mujoco [(default)]: status ok -> diverged: state exploded at t = 0.2",
    ]
    verdict = json.loads(verdict_file.read_text())
    assert (verdict["passed"], verdict["compared"], verdict["regressions"]) == (False, 5, 3)
    cells = {(c["scenario"], c["engine"], c["setting"]): c for c in verdict["cells"]}
    assert list(cells) == [
        ("slider_crank", "mujoco", DEFAULT),
        ("slider_crank", "exudyn", DEFAULT),
        ("four_bar", "mujoco", DEFAULT),
        ("four_bar", "exudyn", DEFAULT),
        ("four_bar", "exudyn", SWEEP),
        ("cam_roller", "mujoco", DEFAULT),
    ]  # the baseline's order
    expected_growth = {
        ("slider_crank", "mujoco", DEFAULT): (10.0, 1.0, 1.0),
        ("slider_crank", "exudyn", DEFAULT): (2.0, 2.0, 2.0),
        ("four_bar", "mujoco", DEFAULT): (1e-3, 1e-3, 1e-3),
        ("four_bar", "exudyn", SWEEP): (1.0, 1.0, 1.0),
    }
    for key, growth in expected_growth.items():
        measured = [cells[key]["errors"][level]["growth"] for level in gate.LEVELS]
        assert measured == pytest.approx(growth, rel=1e-12), key
        assert cells[key]["status"] == cells[key]["baseline_status"] == "ok"
    assert [cells[k]["passed"] for k in cells] == [False, True, True, False, True, False]
    missing, failed = cells[("four_bar", "exudyn", DEFAULT)], cells[("cam_roller", "mujoco", DEFAULT)]
    assert missing["status"] == "missing" and missing["errors"]["position"]["growth"] is None
    assert failed["status"] == "diverged" and failed["baseline_status"] == "ok"
    assert all(failed["errors"][level]["error"] is None for level in gate.LEVELS)


def test_the_verdict_of_the_10x_cell_turns_at_the_factor(files, capsys) -> None:  # type: ignore[no-untyped-def]
    """Allowing 10.5x the baseline, the cell 10x worse passes; allowing 9.5x, it regresses. (At the
    default 10 exactly, 1e-5 against 10 x 1e-6 = 9.999999999999999e-06 is decided by round-off.)
    The missing row and the failed run regress at any factor."""
    baseline, results = files
    status, text = check(capsys, baseline, results, "--factor", "10.5")
    assert status == 1 and "5 cells compared, 2 regressions:" in text
    assert "slider_crank x mujoco" not in text
    status, text = check(capsys, baseline, results, "--factor", "9.5")
    assert status == 1 and "3 regressions:" in text and "position error 1e-05 > 9.5 x baseline 1e-06" in text


def test_only_the_passing_cells_pass(files, tmp_path: Path, capsys) -> None:  # type: ignore[no-untyped-def]
    """The within-factor and the improved cells alone: exit 0 (the pairs not run are not compared)."""
    baseline, _ = files
    passing = store(tmp_path / "passing", CURRENT[1:3])
    status, text = check(capsys, baseline, passing, "--factor", "3")
    assert status == 0 and text.strip().endswith("2 cells compared, no regressions")


def test_a_new_cell_is_refused_not_passed(files, tmp_path: Path, capsys) -> None:  # type: ignore[no-untyped-def]
    """A cell the baseline lacks: the gate cannot judge it, so `check` ends with one error line, exit
    2, whatever the other cells say."""
    baseline, _ = files
    extended = store(tmp_path / "extended", [*CURRENT[1:3], NEW])
    status = main(["check", "--baseline", str(baseline), "--results", str(extended)])
    captured = capsys.readouterr()
    assert status == 2 and captured.out == ""
    assert captured.err.startswith("mbxval: error: the baseline lacks 1 of the 3 cells")
    assert "spur_gears x mujoco x (default)" in captured.err and captured.err.count("\n") == 1


def test_the_hand_written_baseline_reads_as_written(files) -> None:  # type: ignore[no-untyped-def]
    baseline, _ = files
    cells = gate.read_baseline(baseline)
    assert [(c["scenario"], c["engine"], c["setting"]) for c in cells] == [b[:3] for b in BASELINE]
    assert all(math.isclose(c["error_acceleration"], b[6]) for c, b in zip(cells, BASELINE, strict=True))
