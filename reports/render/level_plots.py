"""The per-scenario figures at all three levels side by side: work-precision (error against run time
over each engine-mode's sweep) and each default run's deviation from the truth over time (which says
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
from matplotlib.ticker import FuncFormatter, LogLocator, NullLocator

from reports.harness.level_error import LEVEL_COLUMNS, level_series
from reports.render.markup import figure_text
from reports.render.plots import FLOOR, MARKERS, colour, legend_entries
from scenarios.trajectory import Trajectory

PEAK_POINTS = 400
PLAIN_DECADE = FuncFormatter(lambda value, _: f"{value:.0e}")  # plain text: no mathtext to parse
MARGINS = {"left": 0.06, "right": 0.84, "bottom": 0.17, "top": 0.84, "wspace": 0.18}


def work_precision(rows: pd.DataFrame, truth: str) -> Figure | None:
    """Run time against error at each level, one line per engine and mode, default ringed."""
    ok = rows[(rows["status"] == "ok") & rows["run_time"].notna()]
    if ok.empty:
        return None
    figure, axes_row = plt.subplots(1, 3, figsize=(13.5, 3.6), sharey=True)
    drawn = False
    for axes, (level, column) in zip(axes_row, LEVEL_COLUMNS.items(), strict=True):
        present = ok[ok[column].notna()] if column in ok else ok.iloc[0:0]
        for k, ((engine, mode), curve) in enumerate(present.groupby(["engine", "mode"], sort=True)):
            curve = curve.sort_values("run_time")
            errors = np.maximum(curve[column].to_numpy(float), FLOOR)
            times = curve["run_time"].to_numpy(float)
            axes.plot(
                errors,
                times,
                marker=MARKERS[k % len(MARKERS)],
                color=colour(engine),
                label=f"{engine} {mode}",
            )
            default = curve["is_default"].to_numpy(bool)
            axes.scatter(errors[default], times[default], s=150, facecolors="none", edgecolors=colour(engine))
            drawn = True
        axes.set_xscale("log")
        axes.set_yscale("log")
        axes.set_xlabel(f"{level} error (dimensionless)")
        axes.set_title(level, fontsize=10)
        axes.grid(True, which="major", alpha=0.3)
    if not drawn:
        plt.close(figure)
        return None
    axes_row[0].set_ylabel("run time [s]")
    finish(figure, axes_row, f"work-precision against the truth ({truth}); ringed: default setting")
    return figure


def deviations(
    truth: Trajectory, runs: dict[str, Trajectory], length: float, rate: float, truth_name: str
) -> Figure | None:
    """Each engine's default run minus the truth, dimensionless, at every grid time and level."""
    figure, axes_row = plt.subplots(1, 3, figsize=(13.5, 3.0), sharex=True)
    lows: list[float] = []
    drawn = False
    for axes, level in zip(axes_row, LEVEL_COLUMNS, strict=True):
        for engine, run in runs.items():
            if not set(truth.bodies) <= set(run.bodies):
                continue
            series = level_series(run, truth, level, length, rate)
            if series is None:
                continue
            values = np.maximum(series, FLOOR)
            axes.plot(*peaks(truth.times, values), color=colour(engine), lw=1.1, label=engine)
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
    label, typeset and measure dozens of ticks per panel, most of a report's render time."""
    for axis in (axes.xaxis, axes.yaxis):
        if axis.get_scale() == "log":
            axis.set_major_locator(LogLocator(numticks=6))
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
