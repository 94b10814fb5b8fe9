"""The report's figures, drawn with matplotlib and returned as base64 PNG for a self-contained page:
work-precision (run time against headline error), trajectory overlays, error over time."""

from __future__ import annotations

import base64
import io
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from reports.harness.metrics import headline_series
from scenarios.trajectory import COLUMNS, Trajectory

FLOOR = 1e-17  # errors of exactly zero are drawn here on log axes
COLOURS = {"reference": "#444444", "mujoco": "#1f77b4", "exudyn": "#d62728", "pinocchio": "#2ca02c"}
OTHER_COLOURS = ("#9467bd", "#8c564b", "#e377c2", "#bcbd22", "#17becf", "#ff7f0e")
MARKERS = "osD^v<>p*h"


def colour(engine: str) -> str:
    if engine in COLOURS:
        return COLOURS[engine]
    return OTHER_COLOURS[sum(map(ord, engine)) % len(OTHER_COLOURS)]


def png(figure: Figure) -> str:
    """The figure as base64 PNG text (and the figure closed)."""
    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", dpi=90, bbox_inches="tight")
    plt.close(figure)
    return base64.b64encode(buffer.getvalue()).decode("ascii")


def work_precision(rows: pd.DataFrame) -> Figure | None:
    """Run time against headline error, log-log, one line per engine and mode over its sweep; the
    default setting ringed. None when no run has both numbers."""
    ok = rows[(rows["status"] == "ok") & rows["error"].notna() & rows["run_time"].notna()]
    if ok.empty:
        return None
    figure, axes = plt.subplots(figsize=(6.4, 4.0))
    for k, ((engine, mode), curve) in enumerate(ok.groupby(["engine", "mode"], sort=True)):
        curve = curve.sort_values("error")
        errors = np.maximum(curve["error"].to_numpy(float), FLOOR)
        times = curve["run_time"].to_numpy(float)
        axes.plot(
            errors, times, marker=MARKERS[k % len(MARKERS)], color=colour(engine), label=f"{engine} {mode}"
        )
        default = curve["is_default"].to_numpy(bool)
        axes.scatter(errors[default], times[default], s=160, facecolors="none", edgecolors=colour(engine))
    axes.set_xscale("log")
    axes.set_yscale("log")
    axes.set_xlabel("headline error (position level, lengths / characteristic length)")
    axes.set_ylabel("run time [s] (min of repeats)")
    axes.grid(True, which="major", alpha=0.3)
    axes.legend(fontsize=8, loc="best")
    axes.set_title("work-precision (ringed: default setting)", fontsize=10)
    return figure


def key_coordinates(truth: Trajectory, characteristic_length: float, limit: int = 3) -> list[tuple[int, int]]:
    """(body index, column) of the coordinate that moves most for each body (lengths scaled by the
    characteristic length to compare with angles), the most moving bodies first."""
    assert truth.position is not None
    ranges = np.ptp(truth.position, axis=0)
    ranges[:, :2] /= characteristic_length
    picks = [(b, int(np.argmax(ranges[b]))) for b in range(len(truth.bodies))]
    picks.sort(key=lambda bc: -ranges[bc])
    return picks[:limit]


def overlays(truth: Trajectory, runs: dict[str, Trajectory], characteristic_length: float) -> Figure:
    """The key position coordinates of the truth (solid) and of each engine's default run (dashed)."""
    picks = key_coordinates(truth, characteristic_length)
    figure, axes_row = plt.subplots(1, len(picks), figsize=(3.6 * len(picks), 2.8), squeeze=False)
    assert truth.position is not None
    for axes, (body, column) in zip(axes_row[0], picks, strict=True):
        name = truth.bodies[body]
        axes.plot(
            truth.times, truth.position[:, body, column], color="black", lw=2.5, alpha=0.35, label="truth"
        )
        for k, (engine, run) in enumerate(runs.items()):
            if run.position is None or name not in run.bodies:
                continue
            values = run.position[:, run.bodies.index(name), column]
            dashes = (4, 2 + k)
            axes.plot(run.times, values, color=colour(engine), lw=1.1, dashes=dashes, label=engine)
        unit = "rad" if column == 2 else "m"
        axes.set_title(f"{name}.{COLUMNS['position'][column]} [{unit}]", fontsize=10)
        axes.set_xlabel("t [s]")
        axes.grid(True, alpha=0.3)
    axes_row[0][0].legend(fontsize=8)
    figure.tight_layout()
    return figure


def error_over_time(
    truth: Trajectory, runs: dict[str, Trajectory], characteristic_length: float
) -> Figure | None:
    """The headline error of each engine's default run at every grid time, log scale."""
    series = {}
    for engine, run in runs.items():
        if run.position is not None and set(truth.bodies) <= set(run.bodies):
            series[engine] = headline_series(run, truth, characteristic_length)
    if not series:
        return None
    figure, axes = plt.subplots(figsize=(6.4, 3.0))
    for engine, values in series.items():
        axes.plot(truth.times, np.maximum(values, FLOOR), color=colour(engine), label=engine)
    axes.set_yscale("log")
    axes.set_xlabel("t [s]")
    axes.set_ylabel("headline error")
    axes.set_title("error over time at the default setting", fontsize=10)
    axes.grid(True, which="major", alpha=0.3)
    axes.legend(fontsize=8)
    # NaN where the truth has no configuration (past a singular one in the stress suite)
    lows = [float(np.nanmin(np.maximum(v, FLOOR))) for v in series.values() if np.any(np.isfinite(v))]
    if lows:
        axes.set_ylim(bottom=max(FLOOR / 2, 10 ** math.floor(math.log10(min(lows)))))
    return figure
