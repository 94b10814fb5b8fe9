"""Error against run time across the whole suite, per engine and mode, summarised over scenarios.

Each rung of an engine's settings ladder (its k-th step size dt from the coarsest, or its k-th
tolerance where it has no step; the steps scale with each scenario's period) is summarised over the
scenarios it ran with a shifted geometric mean, as qpbenchmark does: exp(mean(log(x + s))) - s,
so that neither an error of exactly zero nor a few very fast runs dominate. A run that did not end
`ok` counts with error FAILED_ERROR (off by the whole characteristic scale) and run time the time
limit, so that a setting cannot look good by failing on the hard scenarios. A row that ended `ok`
without a run time (an imported trajectory, `mbxval compare`: made outside mbxval, never timed) has
no place on a time axis and is left off it (`untimed`), never put at the time limit.
"""

from __future__ import annotations

import math
import textwrap
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from reports.render.clock import CPU
from reports.render.level_plots import MARGINS, finish
from reports.render.plots import FLOOR, MARKERS, colour, untimed, value_text
from reports.render.svg_figure import hover
from reports.store import LEVEL_COLUMNS

SHIFT_TIME = 1e-3  # s
SHIFT_ERROR = 1e-15  # dimensionless: double precision
FAILED_ERROR = 1.0
STEP_KEYS = ("dt", "tol", "tolerance")
TITLE_CHARACTERS = 140
"""The longest title line: centred over the 13.5 in figure at 10 pt it stays inside both edges (a
longer one, such as a suite's many truth names, is wrapped, never cut off at the edges)."""
TITLE_LINES = 3
"""At most this many title lines (a longer title ends in '...'; the full truth names are in the tables)."""
TITLE_LINE = 0.045
"""The height of one title line, as a fraction of the 3.9 in figure."""
DEFINITION = (
    "Each point is one engine-mode at its k-th step size (or tolerance) from the coarsest, over "
    f"the scenarios it ran with a shifted geometric mean (shift {SHIFT_ERROR:g} on errors, "
    f"{SHIFT_TIME:g} s on run times); a run that did not end ok counts with error {FAILED_ERROR:g} "
    "and the time limit."
)


def shifted_geometric_mean(values: np.ndarray | list[float], shift: float) -> float:
    array = np.asarray(values, dtype=float)
    array = array[np.isfinite(array)]
    if array.size == 0:
        return math.nan
    return float(np.exp(np.mean(np.log(np.maximum(array, 0.0) + shift))) - shift)


def step_of(label: str) -> float:
    """The step size of a setting label (`dt=...`, else its tolerance); NaN without either."""
    options = dict(part.split("=", 1) for part in label.split(" ")[1:] if "=" in part)
    for key in STEP_KEYS:
        if key in options:
            try:
                return float(options[key])
            except ValueError:
                return math.nan
    return math.nan


def ladder_rungs(runs: pd.DataFrame) -> pd.Series:
    """Each run's place in its engine-mode's ladder on its scenario, 1 for the coarsest step: step
    sizes scale with each scenario's period, so the same place, not the same dt, is summarised."""
    steps = pd.Series([step_of(str(s)) for s in runs["setting"]], index=runs.index).fillna(0.0)
    keys = [runs["scenario"], runs["engine"], runs["mode"]]
    return steps.groupby(keys).rank(method="dense", ascending=False).astype(int)


def untimed_note(frame: pd.DataFrame) -> str:
    """Which rows the time axes leave out and why, in words; "" when there are none."""
    rows = frame[untimed(frame)]
    if rows.empty:
        return ""
    pairs = sorted(
        {f"{engine} on {scenario}" for engine, scenario in zip(rows["engine"], rows["scenario"], strict=True)}
    )
    return (
        f"Not on the time axes: {', '.join(pairs)} (no run time: a trajectory imported with `mbxval "
        "compare`, made and timed outside mbxval). Their errors are in the tables and the deviation plots."
    )


def summary(frame: pd.DataFrame, timeout: float) -> pd.DataFrame:
    """One row per engine, mode and ladder rung: its shifted geometric mean run time and error per
    level, how many scenarios it ran and how many did not end ok (untimed rows left out)."""
    runs = frame[(frame["mode"].astype(str) != "") & ~untimed(frame)].copy()
    runs["rung"] = ladder_rungs(runs)
    records: list[dict[str, Any]] = []
    for (engine, mode, rung), group in runs.groupby(["engine", "mode", "rung"], sort=True):
        ok = group["status"] == "ok"
        times = np.where(ok & group["run_time"].notna(), group["run_time"], timeout)
        record: dict[str, Any] = {
            "engine": engine,
            "mode": mode,
            "rung": rung,
            "scenarios": int(group["scenario"].nunique()),
            "not_ok": int((~ok).sum()),
            "default": bool(group["is_default"].mean() >= 0.5),
            "run_time": shifted_geometric_mean(times, SHIFT_TIME),
        }
        for column in LEVEL_COLUMNS.values():
            values = group[column].to_numpy(float) if column in group else np.full(len(group), np.nan)
            produced = ok.to_numpy() & np.isfinite(values)
            if not produced.any():  # the engine-mode does not produce this level
                record[column] = math.nan
                continue
            scored = np.where(ok.to_numpy(), values, FAILED_ERROR)
            record[column] = shifted_geometric_mean(scored, SHIFT_ERROR)
        records.append(record)
    return pd.DataFrame(records)


def overview_figure(table: pd.DataFrame, truth: str, clock: str = CPU) -> Figure | None:
    """Error (x) against run time (y) on `clock` (reports.render.clock), one panel per level, one
    line per engine-mode."""
    if table.empty:
        return None
    figure, axes_row = plt.subplots(1, 3, figsize=(13.5, 3.9), sharey=True)
    drawn = False
    for axes, (level, column) in zip(axes_row, LEVEL_COLUMNS.items(), strict=True):
        for k, ((engine, mode), curve) in enumerate(table.groupby(["engine", "mode"], sort=True)):
            times = curve["run_time"].to_numpy(float)
            placed = np.isfinite(curve[column].to_numpy(float)) & np.isfinite(times) & (times > 0)
            curve = curve[placed].sort_values("run_time")  # no time limit known: nowhere on the axis
            if curve.empty:
                continue
            drawn = True
            errors = np.maximum(curve[column].to_numpy(float), FLOOR)
            times = curve["run_time"].to_numpy(float)
            label = f"{engine} {mode} ({int(curve['scenarios'].max())})"
            (line,) = axes.plot(
                errors, times, marker=MARKERS[k % len(MARKERS)], color=colour(engine), label=label
            )
            hover(line, [_point_title(row, level, column) for _, row in curve.iterrows()])
            default = curve["default"].to_numpy(bool)
            axes.scatter(errors[default], times[default], s=150, facecolors="none", edgecolors=colour(engine))
        axes.set_xscale("log")
        axes.set_yscale("log")
        axes.set_xlabel(f"{level} error (dimensionless)")
        axes.grid(True, which="major", alpha=0.3)
        axes.set_title(level, fontsize=10)
    if not drawn:
        plt.close(figure)
        return None
    axes_row[0].set_ylabel(f"run time [s], {clock}")
    title = (
        f"error against run time over the suite (shifted geometric mean; truth: {truth}; "
        "ringed: the default on most scenarios; (n): scenarios)"
    )
    lines = textwrap.wrap(title, TITLE_CHARACTERS, max_lines=TITLE_LINES, placeholder=" ...)")
    finish(figure, axes_row, "\n".join(lines))
    # each line past the first takes its height from the panels, which keep their titles clear of it
    figure.subplots_adjust(top=MARGINS["top"] - TITLE_LINE * (len(lines) - 1))
    return figure


def _point_title(row: pd.Series, level: str, column: str) -> str:
    """The hover text of one overview point: what it summarises and its values."""
    return (
        f"{row['engine']} {row['mode']}, step {int(row['rung'])} from the coarsest, over "
        f"{int(row['scenarios'])} scenarios ({int(row['not_ok'])} not ok)\n"
        f"{level} error {value_text(float(row[column]))}, run time {value_text(float(row['run_time']))} s"
    )
