"""The dynamics suite's report section, from stored results alone: the stiffness-step stability map,
each engine's energy drift and constraint drift over time, and a table of what each engine's default
reaches and costs per step. Empty ("") when the results hold no dynamic scenario. The verdicts and
the drift series are read as the run stored them (reports.dynamics.recording), never evaluated."""

from __future__ import annotations

import math
from collections.abc import Callable

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from matplotlib.figure import Figure

import reports.render.markup as markup
from reports.render.first_screen import truth_names
from reports.render.plots import FLOOR, colour, legend_entries
from reports.render.report_data import ReportData, drift_mark, map_cell_rows, number
from reports.store import DRIFT_DEFINITION, DRIFT_SERIES, NOT_RECORDED

SHADES = {
    "stable": "#e6f4e6",
    "drifted": "#fde7c8",
    "unmeasured": "#eeeeee",
    "diverged": "#fbe3e3",
    "failed": "#fbe3e3",
    "timeout": "#fbe3e3",
    "singular": "#fbf5cf",
    "unsupported": "#eeeeee",
}
DYNAMIC_TRUTH = "native dynamics"
"""How the `truth` of a dynamic scenario's rows begins (reports.scoring.truth, reports.dynamics.cases)."""


def dynamic_scenarios(data: ReportData) -> list[str]:
    """The dynamic scenarios of the results (map cells apart), in the report's order: those whose
    rows were measured against the native dynamics."""
    frame = data.frame
    if "truth" not in frame:
        return []
    dynamic = frame["truth"].fillna("").astype(str).str.startswith(DYNAMIC_TRUTH)
    names = set(frame.loc[dynamic, "scenario"].astype(str)) - set(map_cell_rows(frame)["scenario"])
    return [s for s in data.scenarios() if s in names]


def headline(data: ReportData) -> str:
    """One sentence for the first screen: the truth, and per engine its default's worst position
    error over the dynamic scenarios (map cells apart) and how many ran ok."""
    names = dynamic_scenarios(data)
    parts = []
    for engine in data.engines():
        rows = [r for n in names if (r := data.default_row(n, engine)) is not None]
        ok = [float(r["error_position"]) for r in rows if r["status"] == "ok"]
        worst = max((v for v in ok if math.isfinite(v)), default=math.nan)
        parts.append(f"{engine} ok on {len(ok)} of {len(rows)}, worst {number(worst)}")
    truth = truth_names(data.frame[data.frame["scenario"].isin(names)])
    return (
        f"Dynamic scenarios against the truth ({truth}), each engine's default setting: {'; '.join(parts)}."
    )


def stability_figure(data: ReportData, cells: pd.DataFrame) -> Figure | None:
    """One panel per engine: stiffness against step, each cell its default run's stored verdict and
    error."""
    shown = cells[cells["is_default"].astype(bool)]
    if shown.empty:
        return None
    engines = [e for e in data.engines() if e in set(shown["engine"])]
    stiffnesses = sorted({float(k) for k in shown["map_stiffness"]})
    steps = sorted({float(dt) for dt in shown["map_dt"]})
    figure, axes_row = plt.subplots(1, len(engines), figsize=(3.4 * len(engines) + 0.6, 3.4), squeeze=False)
    for axes, engine in zip(axes_row[0], engines, strict=True):
        for _, cell in shown[shown["engine"] == engine].iterrows():
            x, y = steps.index(float(cell["map_dt"])), stiffnesses.index(float(cell["map_stiffness"]))
            verdict, error = str(cell["verdict"]) or NOT_RECORDED, float(cell["error_position"])
            axes.add_patch(plt.Rectangle((x - 0.5, y - 0.5), 1, 1, color=SHADES.get(verdict, "#fff")))
            text = verdict + (f"\n{error:.0e}" if math.isfinite(error) else "")
            axes.text(x, y, text, ha="center", va="center", fontsize=7.5)
        axes.set_xlim(-0.5, len(steps) - 0.5)
        axes.set_ylim(-0.5, len(stiffnesses) - 0.5)
        axes.set_xticks(range(len(steps)), [f"{s:.0e}" for s in steps])
        axes.set_yticks(range(len(stiffnesses)), [f"{k:.0e}" for k in stiffnesses])
        axes.set_xlabel("step dt [s]")
        axes.set_title(markup.figure_text(engine), fontsize=10, color=colour(engine))
    axes_row[0][0].set_ylabel("spring stiffness [N/m]")
    figure.tight_layout()
    return figure


def drift_figure(data: ReportData, names: list[str], label: str) -> Figure | None:
    """One panel per scenario: each engine's default run's stored `label` series (DRIFT_SERIES) over
    time (log scale); a panel none of whose runs stored it says so."""
    panels = [n for n in names if data.truth(n) is not None]
    if not panels:
        return None
    columns = min(3, len(panels))
    rows = math.ceil(len(panels) / columns)
    figure, grid = plt.subplots(rows, columns, figsize=(4.3 * columns, 2.6 * rows), squeeze=False)
    for axes in grid.ravel()[len(panels) :]:
        axes.set_visible(False)
    for axes, name in zip(grid.ravel(), panels, strict=False):
        runs = data.default_trajectories(name)
        stored = {e: run for e, run in runs.items() if DRIFT_SERIES[label] in run.extras}
        for engine, run in stored.items():
            values = run.extras[DRIFT_SERIES[label]]
            axes.semilogy(run.times, np.maximum(values, FLOOR), color=colour(engine), label=engine, lw=1.2)
        title = f"{name} ({NOT_RECORDED})" if runs and not stored else name
        axes.set_title(markup.figure_text(title), fontsize=9)
        axes.set_xlabel("t [s]", fontsize=8)
        axes.tick_params(labelsize=7)
    grid[0][0].set_ylabel(label, fontsize=8)
    handles, labels = legend_entries(grid.ravel())
    if handles:
        figure.legend(handles, labels, loc="upper right", fontsize=8)
    figure.tight_layout(rect=(0, 0, 0.9, 1))
    return figure


def summary_table(data: ReportData, names: list[str]) -> pd.DataFrame:
    """Per scenario and engine: the default's errors, drifts and cost per step, and the best error."""
    records = []
    for name in names:
        rows = data.rows(name)
        for engine in data.engines():
            default = data.default_row(name, engine)
            if default is None:
                continue
            ok = rows[(rows["engine"] == engine) & (rows["status"] == "ok")]
            best = ok.loc[ok["error_position"].idxmin()] if ok["error_position"].notna().any() else None
            best_text = (
                "–"
                if best is None
                else f"{number(best['error_position'])}{drift_mark(best)} ({best['setting']})"
            )
            steps = float(default.get("steps", 0) or 0)
            records.append(
                {
                    "scenario": name,
                    "engine": engine,
                    "default setting": f"{default['setting']} ({default['status']})",
                    "pos": number(default.get("error_position")) + drift_mark(default),
                    "vel": number(default.get("error_velocity")) + drift_mark(default),
                    "energy drift": number(default.get("energy_drift")),
                    "residual at end": number(default.get("constraint_residual_final")),
                    "µs per step": number(1e6 * float(default["run_time"]) / steps) if steps > 0 else "–",
                    "best pos": best_text,
                }
            )
    return pd.DataFrame.from_records(records)


def html_fragment(data: ReportData, image: Callable[[Figure | None, str], str]) -> str:
    """The section as HTML ("" without dynamic results); `image` inlines a figure."""
    names = dynamic_scenarios(data)
    cells = map_cell_rows(data.frame)
    if not names and cells.empty:
        return ""
    parts = ["<h2>Dynamics: drift and stability</h2>"]
    table = summary_table(data, names)
    if not table.empty:
        parts += [
            '<p class="muted">Each engine\'s default setting on each dynamic scenario: errors against the '
            "native truth (dimensionless, as above), energy drift, the constraint residual at the end, "
            "the run time per engine step, and the best position error over the engine's ladder of "
            "settings.</p>",
            f'<div class="wide">{table.to_html(index=False, escape=True, border=0, classes="matrix")}</div>',
        ]
    if not cells.empty:
        definition = next((str(d) for d in cells["verdict_detail"] if str(d)), f"verdicts {NOT_RECORDED}")
        parts += [
            "<h3>Stability map: spring stiffness against step size</h3>",
            image(stability_figure(data, cells), "stability map"),
            f'<p class="muted">The stiff spring (stiff_spring/k..._dt...) at each engine\'s default setting '
            f"for the cell's output step. {markup.escape(definition)}.</p>",
        ]
    if names:
        parts += [
            "<h3>Energy drift over time</h3>",
            image(drift_figure(data, names, "energy drift"), "energy drift"),
            f'<p class="muted">{markup.escape(DRIFT_DEFINITION)}.</p>',
            "<h3>Constraint drift over time</h3>",
            image(drift_figure(data, names, "constraint residual"), "constraint drift"),
            '<p class="muted">The largest constraint residual of each default run at each time, lengths '
            "in characteristic lengths, evaluated on the run's positions by the native constraint "
            "equations.</p>",
        ]
    return "\n".join(parts)
