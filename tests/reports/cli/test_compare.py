"""`mbxval compare` from the command line: the verdict per level for a trajectory of known error,
the row added beside the engines with --out, and every bad input as one line, exit 2, nothing
written."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import scenarios
from reports.cli.main import main
from reports.render.report_data import ReportData
from reports.run import engine_facts
from reports.store.results_store import read_results, read_trajectories
from scenarios import Trajectory
from scenarios.closed_form import exact

OFFSET = 4.0e-4  # m, added to the rod's x: the position error is OFFSET / L = 2e-3 for L = 0.2 m


def _known(path: Path) -> Path:
    """The slider-crank's closed form with OFFSET added to the rod's x, as CSV."""
    truth = exact(scenarios.build("slider_crank"))
    position = np.array(truth.position)
    position[:, truth.bodies.index("rod"), 0] += OFFSET
    moved = Trajectory(truth.times, truth.bodies, position, truth.velocity, truth.acceleration)
    moved.to_frame().to_csv(path, index=False, float_format="%.17g")
    return path


def _compare(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    code = main(["compare", *argv])
    out, err = capsys.readouterr()
    return code, out, err


def test_verdict_per_level(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = _compare(capsys, "slider_crank", str(_known(tmp_path / "my_tool.csv")))
    assert (code, err) == (0, "")
    lines = {line.split()[0]: line.split() for line in out.splitlines() if line.strip()}
    assert out.startswith("my_tool: ")  # the label defaults to the file's stem
    assert "truth: closed form" in out
    assert float(lines["position"][1]) == pytest.approx(OFFSET / 0.2, rel=1e-2)
    assert lines["position"][2] == "red"  # 2e-3 on the report's scale from 1e-14 to 1e-1
    assert float(lines["velocity"][1]) < 1e-12 and lines["velocity"][2] == "green"
    assert len(out.splitlines()) < 25  # one screen


def test_out_adds_the_row_beside_the_engines(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    store = tmp_path / "results"
    assert (
        main(["run", "--out", str(store), "--quiet", "--scenario", "spur_gears", "--engine", "reference"])
        == 0
    )
    truth = exact(scenarios.build("spur_gears"))
    position = np.array(truth.position)
    position[:, 0, 2] += 1e-6  # rad on the first gear
    csv = tmp_path / "gears.csv"
    frame = Trajectory(truth.times, truth.bodies, position=position).to_frame()
    frame.drop(columns=[c for c in frame.columns if c.startswith("gear_out.")]).to_csv(csv, index=False)
    capsys.readouterr()
    code, out, err = _compare(capsys, "spur_gears", str(csv), "--label", "other_tool", "--out", str(store))
    assert (code, err) == (0, ""), err
    assert f"added to {store} as engine 'other_tool'" in out
    beside = {line.split()[0]: line.split() for line in out.split("in the store")[1].splitlines()[1:3]}
    assert set(beside) == {"reference", "other_tool"}  # the engine's default row beside the import
    assert float(beside["other_tool"][1]) == pytest.approx(1e-6, rel=1e-2)
    assert beside["other_tool"][2] == "nan"  # no velocity in the file
    frame, meta = read_results(store)
    row = frame[frame["engine"] == "other_tool"].iloc[0]
    assert row["scenario"] == "spur_gears" and row["setting"] == "imported" and bool(row["is_default"])
    assert row["error_position"] == pytest.approx(1e-6, rel=1e-6)
    assert "imported trajectory" in row["measures"] and row["truth"] == "closed form"
    assert np.isnan(row["error_velocity"]) and "velocity not in the file" in row["message"]
    assert "bodies not in the file, not scored: gear_out" in row["message"]
    assert set(frame["engine"]) == {"reference", "other_tool"}  # the engine's rows are kept
    assert meta["imported"] == {"other_tool": str(csv)}
    assert meta["engine_colours"] == engine_facts.colours(["reference"])  # the label declares none
    assert ("spur_gears", "other_tool", "imported") in read_trajectories(store)
    data = ReportData.load(store)
    assert data.engines() == ["reference", "other_tool"]
    assert main(["report", str(store)]) == 0
    assert "other_tool" in (store / "summary.md").read_text()


def _bad(tmp_path: Path, edit) -> Path:  # type: ignore[no-untyped-def]
    frame = exact(scenarios.build("slider_crank")).to_frame()
    path = tmp_path / "bad.csv"
    edited = edit(frame)
    if isinstance(edited, str):
        path.write_text(edited)
    else:
        edited.to_csv(path, index=False, float_format="%.17g")
    return path


def _set(frame: pd.DataFrame, column: str, row: int, value: object) -> pd.DataFrame:
    frame = frame.astype(object)
    frame.loc[row, column] = value
    return frame


def _shift_times(frame: pd.DataFrame) -> pd.DataFrame:
    frame = frame.copy()
    frame.loc[10:, "t"] += 1e-6
    return frame


BAD = {
    "unknown column": (
        lambda f: f.rename(columns={"rod.x": "rd.x"}),
        "bad.csv: line 1, column 11: not a column name of slider_crank (did you mean 'rod.x'?); "
        "expected t, then the bodies crank, rod, slider",
    ),
    "column of no body": (
        lambda f: f.assign(energy=1.0),
        "bad.csv: line 1, column 29: not a column name of slider_crank",
    ),
    "no time column": (lambda f: f.drop(columns=["t"]), "bad.csv: no column 't' (the time)"),
    "too few rows": (
        lambda f: f.iloc[:-1],
        "bad.csv: has 200 time rows; the grid of slider_crank has 201 times, 200 steps from 0 to",
    ),
    "shifted times": (
        _shift_times,
        "bad.csv: the times are not the grid of slider_crank (201 times, 200 steps from 0 to "
        "0.12566370614359174 s): 191 of 201 differ, by up to 1e-06 s; the first at row 11",
    ),
    "nan value": (
        lambda f: _set(f, "rod.vx", 5, np.nan),
        "bad.csv: line 7, column 14: empty; expected a finite number",
    ),
    "nan text": (
        lambda f: _set(f, "rod.vx", 5, "nan"),
        "bad.csv: line 7, column 14: not finite",
    ),
    "infinite value": (
        lambda f: _set(f, "crank.ay", 7, "-inf"),
        "bad.csv: line 9, column 9: not finite",
    ),
    "text value": (
        lambda f: _set(f, "slider.x", 2, "abc"),
        "bad.csv: line 4, column 20: not a number; expected a finite number",
    ),
    "partial level": (
        lambda f: f.drop(columns=["rod.theta"]),
        "bad.csv: body 'rod' has rod.x, rod.y but not rod.theta: the position level's three columns",
    ),
    "no output body": (
        lambda f: f[["t"]],
        "bad.csv: has no column of the output bodies of slider_crank: crank, rod, slider",
    ),
    "empty file": (lambda f: "", "bad.csv: not a CSV table: "),
    "header only": (lambda f: "t,crank.x\n", "bad.csv: has no rows"),
    "not a table": (lambda f: 'a,b\n1,2,3,"\n', "bad.csv: not a CSV table: "),
}


@pytest.mark.parametrize("case", BAD)
def test_bad_trajectory_is_one_line_and_writes_nothing(
    case: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    edit, expected = BAD[case]
    path, out = _bad(tmp_path, edit), tmp_path / "results"
    code, stdout, err = _compare(capsys, "slider_crank", str(path), "--out", str(out))
    assert code == 2 and stdout == ""
    assert err.startswith(f"mbxval: error: {tmp_path}/{expected}"), err
    assert err.count("\n") == 1
    assert not out.exists()


def test_unreadable_file(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    code, _, err = _compare(capsys, "slider_crank", str(tmp_path / "nowhere.csv"))
    assert (
        code == 2
        and err == f"mbxval: error: {tmp_path}/nowhere.csv: cannot read: No such file or directory\n"
    )
    (tmp_path / "binary.csv").write_bytes(b"\xff\xfe\x00\x81t,x\n")
    code, _, err = _compare(capsys, "slider_crank", str(tmp_path / "binary.csv"))
    assert code == 2 and err.startswith(f"mbxval: error: {tmp_path}/binary.csv: not UTF-8 text")


@pytest.mark.parametrize(
    ("argv", "expected"),
    [
        (["--label", "mujoco"], "--label 'mujoco' is the name of an engine or of the truth"),
        (["--label", " "], "--label must not be empty"),
        (["--set", "omega=-0"], "slider_crank: omega"),
    ],
)
def test_bad_arguments(
    argv: list[str], expected: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    csv = _known(tmp_path / "t.csv")
    code, _, err = _compare(capsys, "slider_crank", str(csv), *argv, "--out", str(tmp_path / "out"))
    assert code == 2 and err.startswith("mbxval: error: ") and expected in err, err
    assert not (tmp_path / "out").exists()


def test_set_changes_the_grid_it_expects(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """--set steps=20 asks for the 20-step grid: the 200-step file no longer fits, a 20-step one does."""
    csv = _known(tmp_path / "t.csv")
    code, _, err = _compare(capsys, "slider_crank", str(csv), "--set", "steps=20")
    assert code == 2 and "has 201 time rows; the grid of slider_crank has 21 times" in err
    scenario = scenarios.build("slider_crank", overrides={"steps": 20})
    exact(scenario).to_frame().to_csv(tmp_path / "coarse.csv", index=False, float_format="%.17g")
    code, out, _ = _compare(capsys, "slider_crank", str(tmp_path / "coarse.csv"), "--set", "steps=20")
    assert code == 0 and "21 times" in out
