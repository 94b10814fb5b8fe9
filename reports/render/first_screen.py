"""The report's first screen: what the native solver's agreement with the closed forms is, the
scenario x engine matrix at every level, and how far the engines' default runs lie from each other."""

from __future__ import annotations

import json
import math
from typing import Any

import pandas as pd

import reports.render.markup as markup
from reports.render.report_data import ReportData, drift_mark, number
from reports.store import CLOSED_FORM, LEVEL_COLUMNS, NOT_RECORDED

BEST, WORST = -14.0, -1.0  # log10 error drawn fully green, fully red
LEVEL_LETTERS = {"position": "pos", "velocity": "vel", "acceleration": "acc", "force": "force"}
MATRIX_COLUMNS: dict[str, str] = {str(k): v for k, v in LEVEL_COLUMNS.items()} | {"force": "error_force"}
"""The matrix's columns per engine: the three levels, then the forces (scoring.forces), whose truth
is always the native solver's."""
SPAN = f'colspan="{len(MATRIX_COLUMNS)}"'


def native_line(frame: pd.DataFrame, native: str) -> str:
    """One sentence: the native solver's (engine `native`, as the store records it) worst error
    against the closed forms, per level."""
    if not native:
        return "The native solver's name is not recorded in these results (a store from before it was)."
    if "truth" not in frame:
        return "The native solver was not measured against closed forms (results without a truth column)."
    runs = frame[(frame["engine"] == native) & frame["is_default"].astype(bool)]
    closed = runs[runs["truth"] == CLOSED_FORM]
    if closed.empty:
        return "The native solver has no run against a closed form in these results."
    bad = closed[closed["status"] != "ok"]
    worst = []
    for level, column in LEVEL_COLUMNS.items():
        values = closed.loc[closed["status"] == "ok", column].astype(float)
        if values.notna().any():
            where = str(closed.loc[values.idxmax(), "scenario"])
            worst.append(f"{level} {number(float(values.max()))} ({where})")
    others = int(runs["scenario"].nunique() - closed["scenario"].nunique())
    line = (
        f"Native solver against the closed forms, at its default setting on "
        f"{closed['scenario'].nunique()} scenarios: worst error {', '.join(worst)}"
    )
    if not bad.empty:
        line += f"; not ok on {', '.join(sorted(bad['scenario']))}"
    if others:
        line += f". {others} scenario(s) have no closed form: there the truth is the native solver refined"
    return line + "."


def cell_colour(error: float) -> str:
    """Green (small) to red (large) by log10 error."""
    share = (math.log10(max(error, 1e-300)) - BEST) / (WORST - BEST)
    share = min(max(share, 0.0), 1.0)
    hue = 120.0 * (1.0 - share)
    return f"hsl({hue:.0f}, 65%, 82%)"


def level_matrix(data: ReportData) -> str:
    """scenario x (engine, level) at each engine's default setting: the error coloured by its log,
    the status where the run was not ok, a dash for a level the engine does not produce."""
    engines = data.engines()
    top = "".join(f"<th {SPAN}>{markup.escape(e)}</th>" for e in engines)
    sub = "".join(_heading(lv) for _ in engines for lv in MATRIX_COLUMNS)
    body = []
    for scenario in data.scenarios():
        cells = []
        for engine in engines:
            cells += matrix_cells(data.default_row(scenario, engine))
        truth = _truth_of(data, scenario)
        link = f'<a href="#{markup.anchor(scenario)}">{markup.escape(scenario)}</a>'
        body.append(f'<tr><th title="truth: {markup.escape(truth)}">{link}</th>{"".join(cells)}</tr>')
    head = f'<tr><th rowspan="2">scenario</th>{top}</tr><tr>{sub}</tr>'
    return f'<table class="matrix">{head}{"".join(body)}</table>'


def matrix_cells(row: pd.Series | None) -> list[str]:
    """One engine's three cells of a matrix row (one spanning cell where it did not run ok)."""
    if row is None:
        return [f'<td class="notrun" {SPAN}>not run</td>']
    status = str(row["status"])
    if status != "ok":
        tip = markup.escape(f"{row['setting']}: {row['message']}")
        return [f'<td class="{markup.escape(status)}" {SPAN} title="{tip}">{markup.escape(status)}</td>']
    cells = []
    mark = drift_mark(row)  # stored when the run was made (scoring.self_check)
    why = f"; {row['self_check']}" if mark else ""
    for level, column in MATRIX_COLUMNS.items():
        value = float(row[column]) if column in row and row[column] is not None else math.nan
        force = ' class="force"' if level == "force" else ""
        if math.isnan(value):
            missing = "no forces reported" if force else "level not produced"
            cells.append(f'<td class="notrun{" force" if force else ""}" title="{missing}">–</td>')
        else:
            style = f'style="background:{cell_colour(value)}"'
            tip = markup.escape(f"{row['setting']}{why}")
            cells.append(f'<td{force} {style} title="{tip}">{value:.0e}{mark}</td>')
    return cells


def _heading(level: str) -> str:
    if level == "force":
        tip = "driving forces and joint reactions against the native solver's (scoring.forces)"
        return f'<th class="force" title="{tip}">{LEVEL_LETTERS[level]}</th>'
    return f"<th>{LEVEL_LETTERS[level]}</th>"


def _truth_of(data: ReportData, scenario: str) -> str:
    return truth_names(data.rows(scenario))


def truth_names(rows: pd.DataFrame) -> str:
    """The truths the rows were measured against, most used first ("unnamed" for old results)."""
    if "truth" not in rows:
        return "unnamed"
    counts = rows["truth"][rows["truth"].astype(str) != ""].astype(str).value_counts()
    return " / ".join(counts.index) or "none"


def agreement_frame(data: ReportData) -> pd.DataFrame:
    """Per scenario and level: the pair of engines whose default runs differ most, and by how much,
    as the rows stored it (run.recording); NOT_RECORDED where a store with two runs lacks it."""
    records: list[dict[str, Any]] = []
    for scenario in data.scenarios():
        rows = data.rows(scenario)
        stored = [str(a) for a in rows["agreement"] if str(a or "")] if "agreement" in rows else []
        runs = data.default_trajectories(scenario)
        if not stored and len(runs) < 2:
            continue
        found: dict[str, Any] = json.loads(stored[0]) if stored else {"engines": len(runs), "levels": None}
        levels: dict[str, Any] | None = found["levels"]
        record: dict[str, Any] = {"scenario": scenario, "engines": found["engines"]}
        for level in LEVEL_COLUMNS:
            pair = None if levels is None else levels.get(level)
            text = "–" if pair is None else f"{number(pair[2])} ({pair[0]}–{pair[1]})"
            record[level] = NOT_RECORDED if levels is None else text
        records.append(record)
    return pd.DataFrame(records)


def scenario_rate(data: ReportData, scenario: str) -> float:
    """The characteristic rate stored with the rows (NaN in rows stored before it was: the levels
    it scales then compare as not recorded)."""
    rows = data.rows(scenario)
    return float(rows["characteristic_rate"].iloc[0]) if "characteristic_rate" in rows else math.nan
