"""The dynamics suite's stability map: for every engine, setting and map cell (stiffness against
the step), whether the run stayed stable and accurate, drifted, or broke.

The verdict of a stored row, from the stored results alone:
    stable      ok, position error and energy drift both at most DRIFTED
    drifted     ok as a run, but its position error or energy drift above DRIFTED
    unmeasured  ok as a run, but neither could be measured (no truth, no velocities)
    diverged, failed, timeout, singular, unsupported: the engine's own outcome
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import pandas as pd

from reports.dynamics.cases import map_cells

DRIFTED = 1e-2
"""A run whose position error (dimensionless) or energy drift exceeds this has drifted."""
VERDICTS = ("stable", "drifted", "unmeasured", "diverged", "singular", "failed", "timeout", "unsupported")


@dataclass(frozen=True)
class Cell:
    """One engine's run at one map cell."""

    engine: str
    mode: str
    setting: str
    is_default: bool
    stiffness: float
    dt: float
    verdict: str
    error: float
    energy_drift: float
    detail: str


def verdict(row: pd.Series) -> str:
    """The verdict of one stored row (see the module docstring)."""
    status = str(row["status"])
    if status != "ok":
        return status if status in VERDICTS else "failed"
    measured = [v for v in (_value(row, "error_position"), _value(row, "energy_drift")) if math.isfinite(v)]
    if not measured:
        return "unmeasured"
    return "drifted" if max(measured) > DRIFTED else "stable"


def map_rows(frame: pd.DataFrame) -> list[Cell]:
    """Every stored run at a map cell."""
    cells = map_cells()
    out = []
    for _, row in frame[frame["scenario"].isin(cells)].iterrows():
        values = cells[str(row["scenario"])]
        out.append(
            Cell(
                engine=str(row["engine"]),
                mode=str(row["mode"]),
                setting=str(row["setting"]),
                is_default=bool(row["is_default"]),
                stiffness=values["stiffness"],
                dt=values["dt"],
                verdict=verdict(row),
                error=_value(row, "error_position"),
                energy_drift=_value(row, "energy_drift"),
                detail=str(row.get("message", "") or ""),
            )
        )
    return out


def _value(row: pd.Series, column: str) -> float:
    value = row.get(column, math.nan)
    try:
        return float(value)
    except (TypeError, ValueError):
        return math.nan
