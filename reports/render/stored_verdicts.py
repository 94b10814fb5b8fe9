"""The verdicts a report shows, as the rows stored them when the run was made (the verdict columns
of reports.store.columns, decided by reports.stress.recording and reports.dynamics.stability): read,
never judged. A row stored before the verdicts were recorded shows NOT_RECORDED."""

from __future__ import annotations

import math

import pandas as pd

from reports.render.report_data import is_swept
from reports.store import LOST, NOT_RECORDED, Judgement

STRESS_SUITE = "stress"
"""The suite whose rows the stability map shows."""

__all__ = ["LOST", "NOT_RECORDED", "STRESS_SUITE", "Judgement", "judgement", "judgements", "stress_rows"]


def judgement(row: pd.Series) -> Judgement:
    """The verdict stored in `row` (NOT_RECORDED where it has none)."""
    verdict = str(row.get("verdict") or "")
    return Judgement(
        str(row["scenario"]),
        str(row["engine"]),
        str(row["setting"]),
        bool(row["is_default"]),
        verdict or NOT_RECORDED,
        _float(row.get("verdict_time")),
        _float(row.get("verdict_error")) if verdict else _float(row.get("error")),
        _float(row.get("constraint_residual")),
        str(row.get("verdict_detail") or ""),
    )


def judgements(rows: pd.DataFrame) -> list[Judgement]:
    return [judgement(row) for _, row in rows.iterrows()]


def stress_rows(frame: pd.DataFrame) -> pd.DataFrame:
    """The rows of the stress cases, in the cases' order (as recorded); in a store from before the
    cases were recorded, every row off a sweep, in the order the cases were first run."""
    ranks = frame["case_rank"].fillna(-1).astype(int) if "case_rank" in frame else pd.Series(-1, frame.index)
    if (ranks >= 0).any():
        rows = frame[ranks >= 0].assign(_order=ranks[ranks >= 0])
    else:
        rows = frame[~is_swept(frame)]
        first = rows.groupby("scenario")["recorded_at"].transform("min") if "recorded_at" in rows else ""
        rows = rows.assign(_order=first)
    return rows.sort_values(["_order", "engine"], kind="stable").drop(columns="_order")


def _float(value: object) -> float:
    try:
        return float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        return math.nan
