"""The dynamics suite's report section, from stored results alone: the stiffness-step stability map,
each engine's energy drift and constraint drift over time, and a table of what each engine's default
reaches and costs per step. Empty ("") when the results hold no dynamic scenario."""

from __future__ import annotations

import math
from collections.abc import Callable

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from matplotlib.figure import Figure

import adapters
from reference_solver import constraint_residual
from reports.dynamics.cases import SINGULAR_PASSAGES, TRUTH_RTOL, is_dynamic, map_cells
from reports.dynamics.stability import DRIFTED, Cell, map_rows
from reports.harness.energy_drift import DRIFT_DEFINITION, drift_series
from reports.render import markup
from reports.render.plots import FLOOR, colour, legend_entries
from reports.render.report_data import ReportData, number, stored_scenario
from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory

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
Series = Callable[[Scenario, Trajectory, Trajectory], np.ndarray]


def dynamic_scenarios(data: ReportData) -> list[str]:
    """The dynamic scenarios of the results (map cells apart), in the report's order."""
    cells = map_cells()
    return [s for s in data.scenarios() if is_dynamic(s) and s not in cells]


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
    truth = (
        f"the native forward dynamics (DOP853 at rtol {TRUTH_RTOL:g}; "
        f"{', '.join(f'{f} {r:g}' for f, r in SINGULAR_PASSAGES.items())} through its singular passage)"
    )
    return f"Dynamic scenarios against {truth}, each engine's default setting: {'; '.join(parts)}."


def stability_figure(cells: list[Cell]) -> Figure | None:
    """One panel per engine: stiffness against step, each cell its default run's verdict and error."""
    shown = [c for c in cells if c.is_default]
    if not shown:
        return None
    known = adapters.names()
    engines = sorted(
        {c.engine for c in shown}, key=lambda e: (known.index(e) if e in known else len(known), e)
    )
    stiffnesses = sorted({c.stiffness for c in shown})
    steps = sorted({c.dt for c in shown})
    figure, axes_row = plt.subplots(1, len(engines), figsize=(3.4 * len(engines) + 0.6, 3.4), squeeze=False)
    for axes, engine in zip(axes_row[0], engines, strict=True):
        for cell in (c for c in shown if c.engine == engine):
            x, y = steps.index(cell.dt), stiffnesses.index(cell.stiffness)
            axes.add_patch(plt.Rectangle((x - 0.5, y - 0.5), 1, 1, color=SHADES.get(cell.verdict, "#fff")))
            text = cell.verdict + (f"\n{cell.error:.0e}" if math.isfinite(cell.error) else "")
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


def drift_figure(data: ReportData, names: list[str], series: Series, label: str) -> Figure | None:
    """One panel per scenario: each engine's default run's `series` over time (log scale)."""
    panels = [(n, s) for n in names if (s := stored_scenario(n)) is not None and data.truth(n) is not None]
    if not panels:
        return None
    columns = min(3, len(panels))
    rows = math.ceil(len(panels) / columns)
    figure, grid = plt.subplots(rows, columns, figsize=(4.3 * columns, 2.6 * rows), squeeze=False)
    for axes in grid.ravel()[len(panels) :]:
        axes.set_visible(False)
    for axes, (name, scenario) in zip(grid.ravel(), panels, strict=False):
        truth = data.truth(name)
        assert truth is not None
        for engine, run in data.default_trajectories(name).items():
            try:
                values = series(scenario, run.select(truth.bodies), truth)
            except (ValueError, KeyError, IndexError):
                continue
            axes.semilogy(run.times, np.maximum(values, FLOOR), color=colour(engine), label=engine, lw=1.2)
        axes.set_title(markup.figure_text(name), fontsize=9)
        axes.set_xlabel("t [s]", fontsize=8)
        axes.tick_params(labelsize=7)
    grid[0][0].set_ylabel(label, fontsize=8)
    handles, labels = legend_entries(grid.ravel())
    if handles:
        figure.legend(handles, labels, loc="upper right", fontsize=8)
    figure.tight_layout(rect=(0, 0, 0.9, 1))
    return figure


def residual_series(scenario: Scenario, run: Trajectory, truth: Trajectory) -> np.ndarray:
    """The run's scaled constraint residual at each time (the truth is not needed)."""
    return np.abs(constraint_residual(scenario, run))


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
            best_text = "–" if best is None else f"{number(best['error_position'])} ({best['setting']})"
            steps = float(default.get("steps", 0) or 0)
            records.append(
                {
                    "scenario": name,
                    "engine": engine,
                    "default setting": f"{default['setting']} ({default['status']})",
                    "pos": number(default.get("error_position")),
                    "vel": number(default.get("error_velocity")),
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
    cells = map_rows(data.frame)
    if not names and not cells:
        return ""
    parts = ["<h2>Dynamics: drift and stability</h2>"]
    table = summary_table(data, names)
    if not table.empty:
        parts += [
            '<p class="muted">Each engine\'s default setting on each dynamic scenario: errors against the '
            "native truth (dimensionless, as above), energy drift, the constraint residual at the end, "
            "the run time per engine step, and the best position error over the engine's sweep.</p>",
            f'<div class="wide">{table.to_html(index=False, escape=True, border=0, classes="matrix")}</div>',
        ]
    if cells:
        parts += [
            "<h3>Stability map: spring stiffness against step size</h3>",
            image(stability_figure(cells), "stability map"),
            f'<p class="muted">The stiff spring (stiff_spring/k..._dt...) at each engine\'s default setting '
            f"for the cell's output step. stable: position error and energy drift at most {DRIFTED:g}; "
            "drifted: above; otherwise the engine's own outcome.</p>",
        ]
    if names:
        parts += [
            "<h3>Energy drift over time</h3>",
            image(drift_figure(data, names, drift_series, "energy drift"), "energy drift"),
            f'<p class="muted">{markup.escape(DRIFT_DEFINITION)}.</p>',
            "<h3>Constraint drift over time</h3>",
            image(drift_figure(data, names, residual_series, "constraint residual"), "constraint drift"),
            '<p class="muted">The largest constraint residual of each default run at each time, lengths '
            "in characteristic lengths, evaluated on the run's positions by the native constraint "
            "equations.</p>",
        ]
    return "\n".join(parts)
