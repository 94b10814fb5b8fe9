"""The dynamics suite's stability map: for every engine, setting and map cell (stiffness against
the step), whether the run stayed stable and accurate, drifted, or broke.

The verdict of a row, decided when the run is made (reports.dynamics.recording stores it in the
row's `verdict`, with the cell's stiffness and step; the report reads them):
    stable      ok, position error and energy drift both at most DRIFTED
    drifted     ok as a run, but its position error or energy drift above DRIFTED
    unmeasured  ok as a run, but neither could be measured (no truth, no velocities)
    diverged, failed, timeout, singular, unsupported: the engine's own outcome
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

DRIFTED = 1e-2
"""A run whose position error (dimensionless) or energy drift exceeds this has drifted."""
VERDICTS = ("stable", "drifted", "unmeasured", "diverged", "singular", "failed", "timeout", "unsupported")


def verdict(row: Mapping[str, Any]) -> str:
    """The verdict of one stored row (see the module docstring)."""
    status = str(row["status"])
    if status != "ok":
        return status if status in VERDICTS else "failed"
    measured = [v for v in (_value(row, "error_position"), _value(row, "energy_drift")) if math.isfinite(v)]
    if not measured:
        return "unmeasured"
    return "drifted" if max(measured) > DRIFTED else "stable"


def _value(row: Mapping[str, Any], column: str) -> float:
    value = row.get(column, math.nan)
    try:
        return float(value)
    except (TypeError, ValueError):
        return math.nan
