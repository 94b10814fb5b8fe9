"""The dynamics stability map's verdicts, from rows of known outcome, and their recording in the
rows when the run is made."""

from __future__ import annotations

import math
from pathlib import Path

import pandas as pd
import pytest

from reports.dynamics.cases import map_cells
from reports.dynamics.recording import DEFINITION, record
from reports.dynamics.stability import DRIFTED, verdict
from reports.store.columns import empty_row
from reports.store.results_store import ResultsStore


def _row(status: str = "ok", error: float = 1e-9, drift: float = 1e-10) -> pd.Series:
    return pd.Series({"status": status, "error_position": error, "energy_drift": drift})


@pytest.mark.parametrize(
    ("row", "expected"),
    [
        (_row(), "stable"),
        (_row(error=10 * DRIFTED), "drifted"),
        (_row(drift=10 * DRIFTED), "drifted"),
        (_row(error=math.nan, drift=10 * DRIFTED), "drifted"),
        (_row(error=math.nan, drift=math.nan), "unmeasured"),
        (_row("diverged", math.nan, math.nan), "diverged"),
        (_row("timeout", math.nan, math.nan), "timeout"),
        (_row("unsupported", math.nan, math.nan), "unsupported"),
    ],
)
def test_verdicts(row: pd.Series, expected: str) -> None:
    assert verdict(row) == expected


def test_a_map_cell_row_gets_its_verdict_and_cell_recorded_once(tmp_path: Path) -> None:
    name, values = next(iter(map_cells().items()))
    at_cell = empty_row() | {"scenario": name, "engine": "e", "setting": "m dt=1", "is_default": True}
    elsewhere = at_cell | {"scenario": "four_bar_gravity"}
    store = ResultsStore(tmp_path)
    store.add(at_cell | dict(_row(error=0.5)))
    store.add(elsewhere | dict(_row()))
    assert record(store) == 1
    stored = store.rows[(name, "e", "m dt=1")]
    assert (stored["map_stiffness"], stored["map_dt"], stored["verdict"], stored["verdict_detail"]) == (
        values["stiffness"],
        values["dt"],
        "drifted",
        DEFINITION,
    )
    assert store.rows[("four_bar_gravity", "e", "m dt=1")]["verdict"] == ""
    assert record(store) == 0  # decided once: a recorded verdict is kept
