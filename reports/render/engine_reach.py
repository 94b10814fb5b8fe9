"""What each engine gives out of the box and what it can reach, read off the stored rows alone.

Per engine, over the scenarios of the results:
- untuned: the worst error at each level of its own defaults as a new user's model gets them (the
  rows stored with `is_untuned`; NaN where the engine declares none or the store predates it);
- its default: the worst error at each level of the default its settings rule gives;
- what it reaches: per scenario the best error any of its settings gives (the largest over the
  levels it produces), and the worst of those bests over the scenarios, with the median over the
  scenarios of the run time of each one's best setting;
- the cost of a target (TARGET at every level it produces): per scenario the least run time (on the
  clock the store recorded, reports.render.clock) among
  the settings that meet it, as DiffEqDevTools reads a work-precision set; how many scenarios it
  meets the target on, and the median of those costs.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import pandas as pd

from reports.render.clock import CPU, clock_label
from reports.store import LEVEL_COLUMNS

TARGET = 1e-6
LEVELS = list(LEVEL_COLUMNS.values())


def _worst_level(rows: pd.DataFrame) -> pd.Series:
    """Each row's largest error over the levels it produced (NaN where it produced none)."""
    return rows[LEVELS].astype(float).max(axis=1, skipna=True)


def reach(frame: pd.DataFrame, target: float = TARGET) -> pd.DataFrame:
    """One row per engine: untuned and default worst per level, worst best-reached and the median
    run time of the best settings, scenarios meeting `target` at every level, and the median least
    run time that meets it (NaN where none does)."""
    ok = frame[frame["status"] == "ok"].copy()
    ok["worst"] = _worst_level(ok)
    ok["run_time"] = pd.to_numeric(ok["run_time"], errors="coerce")
    ok = ok[ok["worst"].notna()]
    untuned_flag = ok["is_untuned"] if "is_untuned" in ok else pd.Series(False, index=ok.index)
    ok["untuned"] = untuned_flag.fillna(False).astype(bool)
    rows = []
    for engine, runs in ok.groupby("engine", sort=False):
        defaults = runs[runs["is_default"].astype(bool)]
        untuned = runs[runs["untuned"]]
        best_rows = runs.loc[runs.groupby("scenario")["worst"].idxmin()]
        timed = runs[runs["run_time"].notna() & (runs["worst"] <= target)]
        costs = timed.groupby("scenario")["run_time"].min().astype(float)
        best_costs = best_rows["run_time"].dropna().astype(float)
        rows.append(
            {
                "engine": engine,
                **{f"untuned_{c}": _worst(untuned[c]) for c in LEVELS},
                **{f"default_{c}": _worst(defaults[c]) for c in LEVELS},
                "best_worst": float(best_rows["worst"].max()),
                "best_cost": float(np.median(best_costs)) if best_costs.size else math.nan,
                "scenarios": len(best_rows),
                "reached": int(costs.size),
                "median_cost": float(np.median(costs)) if costs.size else math.nan,
            }
        )
    return pd.DataFrame(rows)


def _worst(errors: pd.Series) -> float:
    """The largest of `errors` (NaN where there is none)."""
    return float(errors.astype(float).max()) if len(errors) else math.nan


def sentences(
    table: pd.DataFrame, target: float = TARGET, clock: str = CPU
) -> list[tuple[str, str, str, str, str]]:
    """(engine, untuned, its default, best reached with its cost, cost of the target) as words, one
    per engine, the costs in seconds of `clock` (reports.render.clock)."""

    def short(value: float) -> str:
        return "-" if math.isnan(value) else f"{value:.1e}"

    out = []
    for row in table.to_dict("records"):
        untuned = " / ".join(short(row[f"untuned_{c}"]) for c in LEVELS)
        if all(math.isnan(row[f"untuned_{c}"]) for c in LEVELS):
            untuned = "none declared"
        default = " / ".join(short(row[f"default_{c}"]) for c in LEVELS)
        best = f"{short(row['best_worst'])} (worst scenario's best setting)"
        if not math.isnan(row["best_cost"]):
            best += f", median {row['best_cost'] * 1e3:.3g} ms a run ({clock})"
        if row["reached"]:
            cost = (
                f"{row['reached']} of {row['scenarios']} scenarios, median "
                f"{row['median_cost'] * 1e3:.3g} ms a run ({clock})"
            )
        else:
            cost = f"not reached on any of {row['scenarios']} scenarios"
        out.append((str(row["engine"]), untuned, default, best, cost))
    return out


HEADERS = (
    "engine",
    "untuned: its own defaults, worst error (pos / vel / acc)",
    "its default by the settings rule, worst error (pos / vel / acc)",
    "best it reaches (over its settings), at what cost",
    f"{TARGET:g} at every level: on how many scenarios, at what cost",
)


def html_table(frame: pd.DataFrame, escape: Callable[[object], str]) -> str:
    """The table of `sentences` as HTML, every cell through `escape`."""
    head = "".join(f"<th>{escape(h)}</th>" for h in HEADERS)
    body = "".join(
        "<tr>" + "".join(f"<td>{escape(cell)}</td>" for cell in row) + "</tr>"
        for row in sentences(reach(frame), clock=clock_label(frame))
    )
    return f"<table><tr>{head}</tr>{body}</table>"


def markdown_lines(frame: pd.DataFrame, text: Callable[[object], str]) -> list[str]:
    """The same table in Markdown, every cell through `text`."""
    rows = ["| " + " | ".join(HEADERS) + " |", "|" + "---|" * len(HEADERS)]
    shown = sentences(reach(frame), clock=clock_label(frame))
    rows += ["| " + " | ".join(text(cell) for cell in row) + " |" for row in shown]
    return rows
