"""What a report draws of every run, measured when the suite finishes: a run shifted by a known
offset from the truth has that offset, over the characteristic length, as its position error at
every time; the engines' widest difference names the pair; both are stored once and read back."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from reports.run.recording import record
from reports.store.columns import ERROR_SERIES, empty_row
from reports.store.results_store import ResultsStore, read_results, read_trajectories
from scenarios.trajectory import Trajectory

LENGTH, RATE, SHIFT = 0.5, 2.0, 1e-3
TIMES = np.linspace(0.0, 1.0, 11)


def _trajectory(shift: float) -> Trajectory:
    position = np.zeros((TIMES.size, 1, 3))
    position[:, 0, 0] = np.cos(RATE * TIMES) + shift
    velocity = np.zeros_like(position)
    velocity[:, 0, 0] = -RATE * np.sin(RATE * TIMES)
    return Trajectory(TIMES, ("crank",), position=position, velocity=velocity)


def _row(engine: str) -> dict[str, object]:
    return empty_row() | {
        "scenario": "s",
        "engine": engine,
        "engine_rank": -1,
        "setting": "default",
        "is_default": True,
        "status": "ok",
        "characteristic_length": LENGTH,
        "characteristic_rate": RATE,
    }


def test_error_series_and_agreement_are_stored_once(tmp_path: Path) -> None:
    store = ResultsStore(tmp_path)
    store.put_truth("s", "closed form", _trajectory(0.0))
    store.add(_row("exact"), _trajectory(0.0))
    store.add(_row("shifted"), _trajectory(SHIFT))
    store.save({})
    store = ResultsStore(tmp_path)
    assert record(store) == 4  # two series, two rows' agreement (names no list holds keep rank -1)
    store.save(store.meta)
    assert record(ResultsStore(tmp_path)) == 0  # nothing changed: nothing rewritten

    shifted = read_trajectories(tmp_path)[("s", "shifted", "default")]
    np.testing.assert_allclose(shifted.extras[ERROR_SERIES["position"]], SHIFT / LENGTH, rtol=1e-9)
    np.testing.assert_array_equal(shifted.extras[ERROR_SERIES["velocity"]], 0.0)
    assert ERROR_SERIES["acceleration"] not in shifted.extras  # a level the run does not have

    frame, _ = read_results(tmp_path)
    found = json.loads(frame["agreement"].iloc[0])
    assert found["engines"] == 2 and found["levels"]["acceleration"] is None
    a, b, value = found["levels"]["position"]
    assert (a, b) == ("exact", "shifted") and abs(value - SHIFT / LENGTH) < 1e-12
    ranks = dict(zip(frame["engine"], frame["engine_rank"], strict=True))
    assert ranks == {"exact": -1, "shifted": -1}  # engines the registry does not list keep -1


def test_a_row_stored_without_ranks_gets_them(tmp_path: Path) -> None:
    store = ResultsStore(tmp_path)
    store.add(_row("reference") | {"scenario": "four_bar/crossed", "scenario_rank": -1})
    assert record(store) == 1
    row = store.rows[("four_bar/crossed", "reference", "default")]
    assert row["engine_rank"] == 0 and row["scenario_rank"] > 0  # four_bar itself comes first


def test_rows_of_a_part_written_before_the_ranks_get_them(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A store whose older part lacks the rank columns, beside a newer part that has them (as
    `compare --out` into a store written by an earlier version makes): its rows read the ranks as missing (-1,
    the declared empty) and are recorded, not a crash."""
    from reports.store import results_store

    older = tuple(c for c in results_store.COLUMNS if c not in ("scenario_rank", "engine_rank"))
    with monkeypatch.context() as patch:
        patch.setattr(results_store, "COLUMNS", older)
        first = ResultsStore(tmp_path)
        for scenario in ("four_bar", "slider_crank"):  # two rows: the newer part does not absorb them
            first.add(_row("reference") | {"scenario": scenario})
        first.save({})
    second = ResultsStore(tmp_path)
    second.add(_row("mujoco") | {"scenario": "four_bar", "scenario_rank": 3, "engine_rank": 1})
    second.save(second.meta)
    store = ResultsStore(tmp_path)
    assert record(store) >= 2
    row = store.rows[("four_bar", "reference", "default")]
    assert row["engine_rank"] == 0 and row["scenario_rank"] >= 0


def test_a_part_written_before_a_column_existed_reads_it_as_its_declared_empty(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Parts of one store may differ in columns (each save writes its own code's): an older part's
    rows read a column added since as the column's declared empty, not as NaN (NaN read as a
    verdict is the text "nan", a verdict that would never be decided)."""
    from reports.store import results_store

    older = tuple(c for c in results_store.COLUMNS if c not in ("verdict", "scenario_rank"))
    with monkeypatch.context() as patch:
        patch.setattr(results_store, "COLUMNS", older)
        first = ResultsStore(tmp_path)
        for engine in ("a", "c"):  # two rows: the newer one-row part does not absorb this one
            first.add(_row(engine) | {"scenario": "four_bar"})
        first.save({})
    second = ResultsStore(tmp_path)
    second.add(_row("b") | {"scenario": "four_bar", "verdict": "ok", "scenario_rank": 3})
    second.save(second.meta)
    frame, _ = read_results(tmp_path)
    rows = frame.set_index("engine")
    assert rows.loc["a", "verdict"] == "" and rows.loc["b", "verdict"] == "ok"
    assert rows.loc["a", "scenario_rank"] == -1 and rows.loc["b", "scenario_rank"] == 3
    assert ResultsStore(tmp_path).rows[("four_bar", "a", "default")]["verdict"] == ""
