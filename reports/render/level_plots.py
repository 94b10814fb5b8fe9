"""The per-scenario figures at all three levels side by side: work-precision (error against run time
over each engine-mode's ladder) and each default run's deviation from the truth over time (which says
more than overlaid trajectories that lie on top of each other)."""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.patches import Rectangle
from matplotlib.ticker import FuncFormatter, LogLocator, NullLocator

from reports.render.clock import time_axis_label
from reports.render.markup import figure_text
from reports.render.plots import FLOOR, MARKERS, colour, legend_entries, swept_value, untimed, value_text
from reports.render.svg_figure import hover
from reports.store import ERROR_SERIES, LEVEL_COLUMNS
from scenarios.trajectory import Trajectory

PEAK_POINTS = 400
PLAIN_DECADE = FuncFormatter(lambda value, _: f"{value:.0e}")  # plain text: no mathtext to parse
NARROW = 1.5  # decades: an axis narrower than this is labelled at 1, 2 and 5 of each decade
STRIP = 0.04  # height of the imported rows' strip, in axes coordinates
IMPORTED = "imported: no run time"
FOOT = 0.15  # the run-time axis's margin, as a fraction of its data range (the strip fits below)
MARGINS = {"left": 0.06, "right": 0.84, "bottom": 0.17, "top": 0.84, "wspace": 0.18}


def work_precision(rows: pd.DataFrame, truth: str) -> Figure | None:
    """Run time against error at each level, one line per engine and mode, default ringed, each
    curve's ends labelled with their swept value; imported rows (no run time) in a strip of their
    own at the foot of each panel, outside the time axis and its limits. Every point's hover title
    gives its engine, setting, scenario, error and run time."""
    ok = rows[rows["status"] == "ok"]
    imported = ok[untimed(ok)]
    ok = ok[~untimed(ok)]
    if ok.empty:  # nothing timed: no time axis to draw (the imported rows are in the tables)
        return None
    figure, axes_row = plt.subplots(1, 3, figsize=(13.5, 3.6), sharey=True)
    drawn = False
    for panel, (axes, (level, column)) in enumerate(zip(axes_row, LEVEL_COLUMNS.items(), strict=True)):
        present = ok[ok[column].notna()] if column in ok else ok.iloc[0:0]
        for k, ((engine, mode), curve) in enumerate(present.groupby(["engine", "mode"], sort=True)):
            curve = curve.sort_values("run_time")
            errors = np.maximum(curve[column].to_numpy(float), FLOOR)
            times = curve["run_time"].to_numpy(float)
            (line,) = axes.plot(
                errors,
                times,
                marker=MARKERS[k % len(MARKERS)],
                color=colour(engine),
                label=f"{engine} {mode}",
            )
            hover(line, [_point_title(row, level, column) for _, row in curve.iterrows()])
            default = curve["is_default"].to_numpy(bool)
            axes.scatter(errors[default], times[default], s=150, facecolors="none", edgecolors=colour(engine))
            if panel == 0:  # once per figure: three panels of labels would hide the points
                _label_ends(axes, curve, errors, times)
            drawn = True
        drawn = _imported_strip(axes, imported, level, column) or drawn
        axes.set_xscale("log")
        axes.set_yscale("log")
        axes.margins(y=FOOT)  # room under the lowest run for the imported rows' strip, with or without them
        axes.set_xlabel(f"{level} error (dimensionless)")
        axes.set_title(level, fontsize=10)
        axes.grid(True, which="major", alpha=0.3)
    if not drawn:
        plt.close(figure)
        return None
    axes_row[0].set_ylabel(time_axis_label(rows))
    finish(figure, axes_row, f"work-precision against the truth ({truth}); ringed: default setting")
    return figure


def _point_title(row: pd.Series, level: str, column: str) -> str:
    time = float(row["run_time"])
    when = f"run time {value_text(time)} s" if math.isfinite(time) else "imported: no run time"
    return (
        f"{row['engine']} {row['setting']} on {row['scenario']}\n"
        f"{level} error {value_text(float(row[column]))}, {when}"
    )


def _label_ends(axes: Axes, curve: pd.DataFrame, errors: np.ndarray, times: np.ndarray) -> None:
    """The swept value beside a curve's first and last point (every point's on hover)."""
    ends = {0, len(curve) - 1}
    for k in sorted(ends):
        text = figure_text(swept_value(str(curve["setting"].iloc[k])))
        axes.annotate(text, (errors[k], times[k]), xytext=(4, 3), textcoords="offset points", fontsize=6)


def _imported_strip(axes: Axes, imported: pd.DataFrame, level: str, column: str) -> bool:
    """Imported rows at their error, in a strip at the foot of the panel (y in axes coordinates,
    so the run-time axis neither holds nor scales to them); True when any is drawn."""
    present = imported[imported[column].notna()] if column in imported else imported.iloc[0:0]
    if present.empty:
        return False
    errors = np.maximum(present[column].to_numpy(float), FLOOR)
    (line,) = axes.plot(
        errors,
        np.full(len(errors), STRIP),
        ls="",
        marker="X",
        color="#555555",
        markeredgecolor="white",
        ms=8,
        transform=axes.get_xaxis_transform(),
        label=IMPORTED,
    )
    hover(line, [_point_title(row, level, column) for _, row in present.iterrows()])
    strip = Rectangle((0, 0), 1, 2 * STRIP, transform=axes.transAxes, color="#eeeeee", zorder=0)
    axes.add_patch(strip)
    return True


def deviations(truth: Trajectory, runs: dict[str, Trajectory], truth_name: str) -> Figure | None:
    """Each engine's default run minus the truth, dimensionless, at every grid time and level, as
    the run stored it (ERROR_SERIES); None where no run stored any."""
    figure, axes_row = plt.subplots(1, 3, figsize=(13.5, 3.0), sharex=True)
    lows: list[float] = []
    drawn = False
    for axes, level in zip(axes_row, LEVEL_COLUMNS, strict=True):
        for engine, run in runs.items():
            if not set(truth.bodies) <= set(run.bodies):
                continue
            series = run.extras.get(ERROR_SERIES[level])
            if series is None:
                continue
            values = np.maximum(series, FLOOR)
            (line,) = axes.plot(*peaks(truth.times, values), color=colour(engine), lw=1.1, label=engine)
            hover(
                line,
                [f"{engine} default run, {level}: largest |run − truth| {value_text(np.nanmax(values))}"],
            )
            if np.any(np.isfinite(values)):
                lows.append(float(np.nanmin(values)))
            drawn = True
        axes.set_yscale("log")
        axes.set_xlabel("t [s]")
        axes.set_title(f"{level}: |run − truth|", fontsize=10)
        axes.grid(True, which="major", alpha=0.3)
    if not drawn:
        plt.close(figure)
        return None
    if lows:
        bottom = max(FLOOR / 2, 10 ** math.floor(math.log10(min(lows))))
        for axes in axes_row:
            axes.set_ylim(bottom=bottom)
    axes_row[0].set_ylabel("dimensionless error")
    finish(figure, axes_row, f"deviation from the truth ({truth_name}) at the default setting")
    return figure


def finish(figure: Figure, axes_row: Sequence[Axes], title: str) -> None:
    """One legend of every line of the panels to the right, the title, light axes, fixed margins
    (measuring every text for a tight layout costs more than drawing the figure)."""
    handles, labels = legend_entries(axes_row)
    figure.legend(handles, labels, fontsize=8, loc="center left", bbox_to_anchor=(0.85, 0.5))
    figure.suptitle(figure_text(title), fontsize=10)
    for axes in axes_row:
        light_log_axes(axes)
    figure.subplots_adjust(**MARGINS)


def light_log_axes(axes: Axes) -> None:
    """Log-log axes with a few decades labelled in plain text (1e-06): many-decade ranges otherwise
    label, typeset and measure dozens of ticks per panel, most of a report's render time. An axis
    spanning less than NARROW decades (a ladder's run times) is labelled at 1, 2 and 5 of each decade,
    so that it carries at least two labels."""
    for axis, (low, high) in ((axes.xaxis, axes.get_xlim()), (axes.yaxis, axes.get_ylim())):
        if axis.get_scale() != "log":
            continue
        narrow = low > 0 and high > 0 and abs(math.log10(high / low)) < NARROW
        axis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0) if narrow else (1.0,), numticks=6))
        axis.set_minor_locator(NullLocator())
        axis.set_major_formatter(PLAIN_DECADE)


def peaks(times: np.ndarray, values: np.ndarray, points: int = PEAK_POINTS) -> tuple[np.ndarray, np.ndarray]:
    """At most `points` samples keeping the largest value of each bin (a plot of an error must not
    hide its peaks by decimation)."""
    if values.size <= points:
        return times, values
    edges = np.linspace(0, values.size, points + 1).astype(int)
    picks = [
        start + int(np.nanargmax(values[start:end])) if np.isfinite(values[start:end]).any() else start
        for start, end in itertools.pairwise(edges)
    ]
    return times[picks], values[picks]
