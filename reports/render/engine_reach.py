"""What each engine gives out of the box and what it can reach, read off the stored rows alone.

Per engine, over the scenarios of the results:
- out of the box: the worst error at each level of its default setting;
- what it reaches: per scenario the best error any of its settings gives (the largest over the
  levels it produces), and the worst of those bests over the scenarios;
- the cost of a target (TARGET at every level it produces): per scenario the least run time among
  the settings that meet it, as DiffEqDevTools reads a work-precision set; how many scenarios it
  meets the target on, and the median of those costs.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import pandas as pd

from reports.harness.columns import LEVEL_COLUMNS

TARGET = 1e-6
LEVELS = list(LEVEL_COLUMNS.values())


def _worst_level(rows: pd.DataFrame) -> pd.Series:
    """Each row's largest error over the levels it produced (NaN where it produced none)."""
    return rows[LEVELS].astype(float).max(axis=1, skipna=True)


def reach(frame: pd.DataFrame, target: float = TARGET) -> pd.DataFrame:
    """One row per engine: default worst per level, worst best-reached, scenarios meeting `target`
    at every level, and the median least run time that meets it (NaN where none does)."""
    ok = frame[frame["status"] == "ok"].copy()
    ok["worst"] = _worst_level(ok)
    ok = ok[ok["worst"].notna()]
    rows = []
    for engine, runs in ok.groupby("engine", sort=False):
        defaults = runs[runs["is_default"].astype(bool)]
        best = runs.groupby("scenario")["worst"].min()
        timed = runs[pd.to_numeric(runs["run_time"], errors="coerce").notna() & (runs["worst"] <= target)]
        costs = timed.groupby("scenario")["run_time"].min().astype(float)
        rows.append(
            {
                "engine": engine,
                **{f"default_{c}": float(defaults[c].astype(float).max()) for c in LEVELS},
                "best_worst": float(best.max()),
                "scenarios": int(best.size),
                "reached": int(costs.size),
                "median_cost": float(np.median(costs)) if costs.size else math.nan,
            }
        )
    return pd.DataFrame(rows)


def sentences(table: pd.DataFrame, target: float = TARGET) -> list[tuple[str, str, str, str]]:
    """(engine, out of the box, best reached, cost of the target) as words, one per engine."""

    def short(value: float) -> str:
        return "-" if math.isnan(value) else f"{value:.1e}"

    out = []
    for row in table.to_dict("records"):
        default = " / ".join(short(row[f"default_{c}"]) for c in LEVELS)
        best = f"{short(row['best_worst'])} (worst scenario's best setting)"
        if row["reached"]:
            cost = (
                f"{row['reached']} of {row['scenarios']} scenarios, median "
                f"{row['median_cost'] * 1e3:.3g} ms a run"
            )
        else:
            cost = f"not reached on any of {row['scenarios']} scenarios"
        out.append((str(row["engine"]), default, best, cost))
    return out


HEADERS = (
    "engine",
    "out of the box: worst error at its default (pos / vel / acc)",
    "best it reaches (over its settings)",
    f"{TARGET:g} at every level: on how many scenarios, at what cost",
)


def html_table(frame: pd.DataFrame, escape: Callable[[object], str]) -> str:
    """The table of `sentences` as HTML, every cell through `escape`."""
    head = "".join(f"<th>{escape(h)}</th>" for h in HEADERS)
    body = "".join(
        "<tr>" + "".join(f"<td>{escape(cell)}</td>" for cell in row) + "</tr>"
        for row in sentences(reach(frame))
    )
    return f"<table><tr>{head}</tr>{body}</table>"


def markdown_lines(frame: pd.DataFrame, text: Callable[[object], str]) -> list[str]:
    """The same table in Markdown, every cell through `text`."""
    rows = ["| " + " | ".join(HEADERS) + " |", "|" + "---|" * len(HEADERS)]
    rows += ["| " + " | ".join(text(cell) for cell in row) + " |" for row in sentences(reach(frame))]
    return rows
