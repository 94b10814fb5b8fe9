"""The dynamics stability map's verdicts, from rows of known outcome."""

from __future__ import annotations

import math

import pandas as pd
import pytest

from reports.dynamics.cases import map_cells
from reports.dynamics.stability import DRIFTED, map_rows, verdict


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


def test_map_rows_read_the_cell_from_the_scenario() -> None:
    name, values = next(iter(map_cells().items()))
    at_cell = {"scenario": name, "engine": "e", "mode": "m", "setting": "m dt=1", "is_default": True}
    elsewhere = {**at_cell, "scenario": "four_bar_gravity"}
    frame = pd.DataFrame([at_cell | dict(_row(error=0.5)), elsewhere | dict(_row())])
    (cell,) = map_rows(frame)
    assert (cell.stiffness, cell.dt, cell.verdict, cell.error) == (
        values["stiffness"],
        values["dt"],
        "drifted",
        0.5,
    )
