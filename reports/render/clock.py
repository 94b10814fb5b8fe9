"""Which clock a store's run times were read on, as a report states it. Runs record the process's
CPU time in `run_time` and the wall clock's beside it (`run_time_wall`, reports.store.columns);
a store written before that has no wall columns (NaN once read) and its `run_time` is wall time.
Read from the stored columns alone, so that an old store renders and says what it shows."""

from __future__ import annotations

import pandas as pd

from reports.store import WALL_COLUMNS

CPU = "CPU"
OLD_WALL = "wall (recorded before CPU time)"
MIXED = "CPU (rows recorded before CPU time: wall)"


def clock_label(rows: pd.DataFrame) -> str:
    """CPU where every timed row recorded a wall time beside its CPU time, OLD_WALL where none did
    (a store from before CPU time, or rows without any time), MIXED where a resume kept old rows."""
    timed = _finite(rows, "run_time") | _finite(rows, "build_time")
    walled = pd.Series(False, index=rows.index)
    for column in WALL_COLUMNS:
        walled |= _finite(rows, column.name)
    if not (timed & walled).any():
        return OLD_WALL
    return MIXED if (timed & ~walled).any() else CPU


def time_axis_label(rows: pd.DataFrame) -> str:
    """The run-time axis's label, naming its clock."""
    return f"run time [s], {clock_label(rows)}"


def _finite(rows: pd.DataFrame, column: str) -> pd.Series:
    if column not in rows:
        return pd.Series(False, index=rows.index)
    values = pd.to_numeric(rows[column], errors="coerce").astype(float)
    return values.notna() & (values != float("inf"))
