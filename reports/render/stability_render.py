"""The stability map as a report section: an HTML fragment and a Markdown section.

Tables, from the verdicts stored in the rows when the run was made (reports.stress.recording; a row
stored before they were recorded shows "not recorded"):
- the map: one row per stress case, one column per engine, each cell the verdict of the engine's
  default setting there, with when it happened, the error reached and the worst residual;
- the settings grids of the cases run at several settings (constraint stiffness against the step,
  mass ratios): one cell per setting;
- the scale and speed cases against their nominal scenario: error and its growth factor;
- the long-horizon drift: error and residual over the first and the last revolution.
Both renderings return "" when the results hold no stress case.
"""

from __future__ import annotations

import math
import re
from collections import Counter

import pandas as pd

import reports.render.markup as markup
from reports.render.markdown_table import markdown_table
from reports.render.report_data import ReportData
from reports.render.stored_verdicts import LOST, STRESS_SUITE, Judgement, judgements, stress_rows
from reports.store import NOT_RECORDED

GROWTH = 10.0
"""An engine whose error at a scale or speed is more than this times its nominal error (both
floored at FLOOR) loses accuracy there."""
FLOOR = 1e-13
ROUGH = 1e-3
"""An ok result with a larger error is shaded apart in the HTML map."""
LEGEND = (
    "Verdicts: ok (on the truth's branch; the error says how close); picked a branch (went on past "
    "a singular configuration, where no truth exists, on the same or the mirrored closure); wrong "
    "branch (on another closure than the truth's); drifted (farther than "
    f"{LOST:g} from the truth and every closure); diverged, singular detected, failed to converge, "
    "failed, timeout, unsupported (the engine's own outcome). @ is when it happened, err the largest "
    "headline error where a truth exists, res the worst constraint residual (relative)."
)
CSS = {
    "ok": "ok",
    "picked a branch": "branch",
    "wrong branch": "bad",
    "drifted": "bad",
    "diverged": "failed",
    "singular detected": "singular",
    "failed to converge": "failed",
    "failed": "failed",
    "timeout": "failed",
    "unsupported": "unsupported",
}
STYLE = (
    "<style>td.sm-ok{background:#e6f4e6}td.sm-rough{background:#f1f4d8}td.sm-branch{background:#e3eefb}td.sm-bad{background:#fde7c8}"
    "td.sm-failed{background:#fbe3e3}td.sm-singular{background:#fbf5cf}td.sm-unsupported{background:#eee;"
    "color:#666}</style>"
)


def _num(value: float) -> str:
    return "–" if not math.isfinite(value) else "0" if value == 0 else f"{value:.1e}"


def cell(v: Judgement) -> str:
    """`verdict @time · err · res`, leaving out what the run does not have."""
    parts = [v.verdict + (f" @{v.time:.4g} s" if math.isfinite(v.time) else "")]
    if "mirrored branch" in v.detail or "same branch" in v.detail:
        parts[0] += " (mirrored)" if "mirrored" in v.detail else " (same)"
    if "truth goes on regular" in v.detail:
        parts[0] += " (truth regular there)"
    parts += [f"err {_num(v.error)}"] if math.isfinite(v.error) else []
    parts += [f"res {_num(v.residual)}"] if math.isfinite(v.residual) else []
    return " · ".join(parts)


def map_frame(found: list[Judgement], engines: list[str], rows: pd.DataFrame) -> pd.DataFrame:
    """case x engine: the default setting's verdict, with the case's probe and expectation (as the
    rows stored them)."""
    records = []
    for name in dict.fromkeys(v.scenario for v in found):
        case = rows[rows["scenario"] == name].iloc[0]
        recorded = int(case["case_rank"]) >= 0
        expected = float(case["case_singular_time"])
        record = {
            "case": name,
            "probes": case["case_probes"] if recorded else NOT_RECORDED,
            "closed form": "–",
        }
        if not recorded:
            record["closed form"] = NOT_RECORDED
        elif math.isfinite(expected):
            record["closed form"] = f"singular @{expected:.4g} s"
        for engine in engines:
            hit = [v for v in found if v.scenario == name and v.engine == engine and v.is_default]
            record[engine] = cell(hit[0]) if hit else "not run"
        records.append(record)
    return pd.DataFrame(records).set_index("case")


GRID = 3
"""A mode run at this many settings or more gets a grid: rows by step, columns by the other options."""


def settings_frames(found: list[Judgement]) -> dict[str, pd.DataFrame]:
    """The settings of each case, engine and mode run at GRID or more settings, as a grid; the
    other settings of an engine run at several, with its default, as one list."""
    groups: dict[tuple[str, str, str], list[Judgement]] = {}
    for v in found:
        groups.setdefault((v.scenario, v.engine, v.setting.split(" ")[0]), []).append(v)
    pairs = Counter((v.scenario, v.engine) for v in found)
    gridded = {(name, engine) for (name, engine, _), g in groups.items() if len(g) >= GRID}
    frames, others = {}, []
    for (name, engine, mode), group in groups.items():
        if len(group) >= GRID:
            frames[f"{name} · {engine} {mode}"] = _grid(group)
            continue
        for v in group:
            if pairs[(name, engine)] > 1 and not (v.is_default and (name, engine) in gridded):
                others.append({"case": name, "engine": engine, "setting": v.setting, "verdict": cell(v)})
    if others:
        frames["other settings, each engine's default among them"] = pd.DataFrame(others).set_index("case")
    return frames


def _grid(group: list[Judgement]) -> pd.DataFrame:
    """Rows by step size dt (largest first), or by the option that varies where the mode has no step
    (a tolerance); columns by the other options that vary; cells verdict and error."""
    options = [_options(v.setting) for v in group]
    keys = [k for k in dict.fromkeys(k for o in options for k in o) if k != "mode"]
    varying = [k for k in keys if len({o.get(k) for o in options}) > 1]
    row_key = "dt" if "dt" in keys else (varying[0] if varying else "")
    columns = [k for k in varying if k != row_key]
    table: dict[str, dict[float, str]] = {}
    for v, o in zip(group, options, strict=True):
        column = " ".join(f"{k}={o[k]}" for k in columns) or "run"
        short = v.verdict + (f" @{v.time:.3g} s" if math.isfinite(v.time) else "")
        table.setdefault(column, {})[_as_number(o.get(row_key, "0"))] = f"{short} {_num(v.error)}".replace(
            " –", ""
        )
    frame = pd.DataFrame(table).fillna("").sort_index(ascending=False)
    frame.index = [f"{row_key or 'run'}={value:.3g}" for value in frame.index]
    return frame[sorted(frame.columns, key=_numeric_key)]


def _as_number(text: str) -> float:
    try:
        return float(text)
    except ValueError:
        return 0.0


def _numeric_key(column: str) -> list[float]:
    """Option values of a column label, as numbers where they are."""
    values = []
    for part in column.split(" "):
        try:
            values.append(float(part.split("=", 1)[-1]))
        except ValueError:
            values.append(0.0)
    return values


def _options(label: str) -> dict[str, str]:
    """A setting label `MODE k=v ...` as {'mode': MODE, k: v, ...}."""
    mode, *pairs = label.split(" ")
    return {"mode": mode, **dict(p.split("=", 1) for p in pairs if "=" in p)}


def similarity_frame(found: list[Judgement], engines: list[str], rows: pd.DataFrame) -> pd.DataFrame:
    """The scale and speed cases: each engine's error and its growth over the nominal case's."""
    defaults = {(v.scenario, v.engine): v for v in found if v.is_default}
    nominals = dict(zip(rows["scenario"], rows["case_nominal"].fillna("").astype(str), strict=True))
    records = []
    for name in dict.fromkeys(v.scenario for v in found):
        if not nominals.get(name) or not any(s == name for s, _ in defaults):
            continue
        record = {"case": name}
        for engine in engines:
            v, nominal = defaults.get((name, engine)), defaults.get((nominals[name], engine))
            record[engine] = "–" if v is None else _growth(v, nominal)
        records.append(record)
    return pd.DataFrame(records).set_index("case") if records else pd.DataFrame()


def _growth(v: Judgement, nominal: Judgement | None) -> str:
    if not math.isfinite(v.error):
        return v.verdict
    if nominal is None or not math.isfinite(nominal.error):
        return _num(v.error)
    factor = max(v.error, FLOOR) / max(nominal.error, FLOOR)
    note = " loses accuracy" if factor > GROWTH else ""
    return f"{_num(v.error)} (×{factor:.3g}){note}"


DRIFT = {
    "err first rev": "error_first_rev",
    "res first rev": "residual_first_rev",
    "err last rev": "error_last_rev",
    "res last rev": "residual_last_rev",
    "angle err at the end [rad]": "angle_error_end",
}
"""The long-horizon table's columns and the stored columns they show."""


def drift_frames(data: ReportData, rows: pd.DataFrame) -> dict[str, pd.DataFrame]:
    """Long cases: each engine's headline error and residual over the first and last revolution, as
    stored with its default run."""
    frames = {}
    recorded = rows[rows["error_first_rev"].notna() & rows["is_default"].astype(bool)]
    for name in dict.fromkeys(recorded["scenario"]):
        records = []
        for engine in data.engines():
            hit = recorded[(recorded["scenario"] == name) & (recorded["engine"] == engine)]
            if not hit.empty:
                records.append(
                    {"engine": engine} | {t: _num(float(hit.iloc[0][c])) for t, c in DRIFT.items()}
                )
        frames[str(name)] = pd.DataFrame(records).set_index("engine")
    return frames


def _tables(data: ReportData) -> list[tuple[str, pd.DataFrame]]:
    if str(data.meta.get("suite", "")) != STRESS_SUITE:  # a default run's near-singular variants
        return []
    rows = stress_rows(data.frame)
    found = judgements(rows)
    if not found:
        return []
    engines = data.engines()
    tables = [("Stability map (each engine's default setting)", map_frame(found, engines, rows))]
    similar = similarity_frame(found, engines, rows)
    if not similar.empty:
        tables.append(("Scale and speed against the nominal case (error, ×growth)", similar))
    tables += [
        (f"Long horizon, {name}: the first and the last revolution", frame)
        for name, frame in drift_frames(data, rows).items()
    ]
    tables += [(f"Settings: {key}", frame) for key, frame in settings_frames(found).items()]
    return tables


def markdown_section(data: ReportData) -> str:
    """The stability map in Markdown ("" without stress results)."""
    tables = _tables(data)
    if not tables:
        return ""
    lines = ["## Stability map", "", LEGEND]
    for title, frame in tables:
        lines += [
            "",
            f"### {markup.markdown_text(title)}",
            "",
            markdown_table(frame, str(frame.index.name or " ")),
        ]
    return "\n".join(lines) + "\n"


def html_fragment(data: ReportData) -> str:
    """The stability map as HTML ("" without stress results)."""
    tables = _tables(data)
    if not tables:
        return ""
    parts = [STYLE, '<h2 id="stability-map">Stability map</h2>', f"<p>{markup.escape(LEGEND)}</p>"]
    for title, frame in tables:
        parts += [f"<h3>{markup.escape(title)}</h3>", _html_table(frame)]
    return "\n".join(parts)


def _html_table(frame: pd.DataFrame) -> str:
    head = "".join(f"<th>{markup.escape(str(n))}</th>" for n in [frame.index.name or "", *frame.columns])
    body = []
    for index, row in frame.iterrows():
        cells = f"<th>{markup.escape(str(index))}</th>" + "".join(_html_cell(str(v)) for v in row)
        body.append(f"<tr>{cells}</tr>")
    return f'<div style="overflow-x:auto"><table><tr>{head}</tr>{"".join(body)}</table></div>'


def _html_cell(text: str) -> str:
    """Coloured by verdict; an ok with an error above ROUGH, and a singular verdict where the truth
    is regular (a false alarm or a jump), stand out."""
    verdict = next((v for v in sorted(CSS, key=len, reverse=True) if text.startswith(v)), None)
    css = CSS[verdict] if verdict else ""
    error = re.search(r"err ([0-9.e+-]+)", text)
    if css == "ok" and error and float(error.group(1)) > ROUGH:
        css = "rough"
    if "truth regular there" in text:
        css = "bad"
    return f'<td class="sm-{css}">{markup.escape(text)}</td>' if css else f"<td>{markup.escape(text)}</td>"
