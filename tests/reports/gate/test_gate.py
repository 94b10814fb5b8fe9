"""The regression gate: `mbxval check` passes against the committed baseline on a fast subset run
for real, and fails with a readable list on a doctored copy of those results."""

from __future__ import annotations

import contextlib
import io
import math
from pathlib import Path

import pandas as pd
import pytest

from reports.cli.main import main
from reports.gate import baselines, gate
from reports.store.results_store import read_results
from tests.support.stores import doctor

BASELINE = baselines.resolve("default")
SUBSET = ["--scenario", "slider_crank", "--scenario", "cam_roller"]


@pytest.fixture(scope="module")
def checked(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, int, str]:
    """The gate run as CI runs it: the quick suite on a subset, every engine."""
    out = tmp_path_factory.mktemp("check")
    text = io.StringIO()
    with contextlib.redirect_stdout(text):
        status = main(["check", "--baseline", str(BASELINE), *SUBSET, "--out", str(out), "--quiet"])
    return out, status, text.getvalue()


def test_check_passes_on_the_baseline(checked) -> None:
    out, status, text = checked
    assert status == 0, text
    assert "no regressions" in text
    frame, _ = read_results(out)
    compared = int(text.split("): ")[1].split(" cells")[0])
    assert compared == len(frame) >= 8  # 2 scenarios x 4 engines, each at its default setting


def run_check(capsys: pytest.CaptureFixture[str], *args: str) -> tuple[int, str]:
    status = main(["check", "--baseline", str(BASELINE), *args])
    return status, capsys.readouterr().out


def test_check_fails_readably_on_a_doctored_copy(checked, tmp_path: Path, capsys) -> None:
    out, _, _ = checked
    original, _ = read_results(out)
    ok = original[(original["status"] == "ok") & original["is_default"]].sort_values("error_position")
    worse, broken = ok.index[-1], ok.index[0]  # errors well above the gate's floor, and any

    def edit(frame: pd.DataFrame) -> None:
        frame.loc[worse, ["error", "error_position"]] = frame.loc[worse, "error_position"] * 1000
        frame.loc[broken, "status"] = "diverged"
        frame.loc[broken, "message"] = "doctored: state exploded"

    copy = doctor(out, tmp_path / "doctored", edit)
    status, text = run_check(capsys, "--results", str(copy))
    assert status == 1
    assert "2 regressions:" in text
    w, b = original.loc[worse], original.loc[broken]
    assert f"{w['scenario']} x {w['engine']} [(default)]: position error " in text
    assert f"> 10 x baseline {w['error']:.3g}" in text
    assert (
        f"{b['scenario']} x {b['engine']} [(default)]: status ok -> diverged: doctored: state exploded"
        in text
    )
    assert read_results(out)[0].equals(original)  # the original results are untouched


def test_update_writes_what_compare_reads(checked, tmp_path: Path, capsys) -> None:
    out, _, _ = checked
    fresh = tmp_path / "baseline.json"
    assert main(["check", "--baseline", str(fresh), "--results", str(out), "--update"]) == 0
    frame, _ = read_results(out)
    assert gate.read_baseline(fresh) == gate.baseline_cells(frame)
    assert gate.judge(gate.read_baseline(fresh), frame).passed


def cells(*rows: tuple[str, str, bool, str, float]) -> pd.DataFrame:
    columns = ("scenario", "engine", "is_default", "status", "error")
    frame = pd.DataFrame(rows, columns=columns)
    frame["setting"] = ["x" if d else "sweep" for d in frame["is_default"]]
    frame["message"] = ""
    return frame


def test_status_order_floor_and_coverage() -> None:
    base = gate.baseline_cells(
        cells(
            ("a", "e1", True, "ok", 1e-15),
            ("a", "e2", True, "unsupported", math.nan),
            ("a", "e3", True, "ok", 1e-6),
            ("a", "e3", False, "ok", 1e-8),
            ("b", "e1", True, "ok", 1e-6),
        )
    )
    same = gate.judge(base, cells(("a", "e1", True, "ok", 5e-13), ("a", "e2", True, "ok", 1e-9)))
    assert same.passed and same.compared == 2  # below the floor; unsupported -> ok is no regression
    worse = gate.judge(
        base,
        cells(
            ("a", "e1", True, "ok", 2e-11),
            ("a", "e2", True, "failed", math.nan),
            ("a", "e3", False, "ok", 1e-8),
        ),
    )
    text = [str(r) for r in worse.regressions]
    assert text == [
        "a x e1 [(default)]: position error 2e-11 > 10 x baseline 1e-15",
        "a x e2 [(default)]: status unsupported -> failed",
        "a x e3 [(default)]: missing: no default-setting row (baseline: ok)",
    ]  # scenario b was not run, so its cells are not compared


def test_an_optional_engine_new_to_the_baseline_is_listed_not_gated() -> None:
    """A baseline made without an optional engine, checked where it is installed: its cells are new,
    said once for the engine; the other engines are gated as before."""
    base = gate.baseline_cells(cells(("a", "e1", True, "ok", 1e-6)))
    verdict = gate.judge(base, cells(("a", "e1", True, "ok", 1e-6), ("a", "e9", True, "failed", math.nan)))
    assert verdict.passed and verdict.compared == 1 and verdict.new == (("e9", 1),)
    lines = gate.describe(verdict, "b.json", 10.0).splitlines()
    assert lines[1:] == ["e9: 1 new cells, not in the baseline, not gated (--update adds them)"]
    worse = gate.judge(base, cells(("a", "e1", True, "ok", 1e-3), ("a", "e9", True, "ok", 1e-6)))
    assert [r.engine for r in worse.regressions] == ["e1"]
    with pytest.raises(
        gate.GateError, match="the baseline lacks 1 of the 2 cells"
    ):  # a known engine's new cell
        gate.judge(base, cells(("a", "e1", True, "ok", 1e-6), ("b", "e1", True, "ok", 1e-6)))


def test_a_baseline_engine_not_installed_is_said_once_not_per_cell() -> None:
    base = gate.baseline_cells(
        cells(
            ("a", "e1", True, "ok", 1e-6),
            ("b", "e1", True, "ok", 1e-6),
            ("a", "e9", True, "ok", 1e-6),
            ("b", "e9", True, "ok", 1e-6),
        )
    )
    verdict = gate.judge(
        base, cells(("a", "e1", True, "ok", 1e-6), ("b", "e1", True, "ok", 1e-6)), not_installed=["e9"]
    )
    assert verdict.passed and verdict.not_installed == (("e9", 2),)
    text = gate.describe(verdict, "b.json", 10.0)
    assert text.splitlines()[1:] == ["e9 not installed: its 2 baseline cells not compared"]
    subset = gate.judge(base, cells(("a", "e1", True, "ok", 1e-6)), not_installed=["e9"])
    assert subset.not_installed == (("e9", 1),)  # only the cells of the scenarios run


def test_update_keeps_the_cells_of_an_engine_not_installed(tmp_path: Path) -> None:
    path = tmp_path / "baseline.json"
    gate.write_baseline(path, cells(("a", "e1", True, "ok", 1e-6), ("a", "e9", True, "ok", 2e-6)), {})
    said = gate.update_baseline(path, cells(("a", "e1", True, "ok", 3e-6)), {}, not_installed=["e9"])
    kept = {(c["engine"], c["error"]) for c in gate.read_baseline(path)}
    assert kept == {("e1", 3e-6), ("e9", 2e-6)}
    assert "kept the 1 cells of e9 as they were: e9 is not installed here" in said
    gate.update_baseline(path, cells(("a", "e1", True, "ok", 3e-6)), {})  # installed, not run: dropped
    assert {c["engine"] for c in gate.read_baseline(path)} == {"e1"}
