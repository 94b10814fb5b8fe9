"""A start-up transient as its own figure, by one rule for every engine: how much worse a run is
near its start than once it has settled, and for how long.

From the dimensionless error at each grid time (scoring.level_error), per level: the steady error
is the largest over the second half of the grid; the excess is the largest over the first half
over the steady error; the time is how long after the first output the error, over the first half,
last exceeds SETTLED times the steady error. The row keeps the level with the largest excess. A run as good
near its start as later shows an excess of at most 1 and a time of 0. The figure is read on the
output grid: a transient shorter than the output spacing is not seen.
"""

from __future__ import annotations

import math

import numpy as np

from reports.scoring.level_error import level_series
from scenarios.scenario import Level, Scenario, characteristic_rate
from scenarios.trajectory import Trajectory

SETTLED = 2.0
"""An error within this factor of the steady error counts as settled."""
MIN_POINTS = 4
"""Fewer grid times than this give no figure (NaN)."""
STARTUP_DEFINITION = (
    "start-up transient, per level: the largest error over the first half of the grid over the largest "
    f"over its second half (startup_excess), and how long after the start the error, within the first half, "
    f"last exceeds {SETTLED:g} times the second half's largest (startup_time, s); the row keeps the "
    "level with the largest excess. Read on the output grid, the same rule for every engine"
)


def startup(
    scenario: Scenario, result: Trajectory, truth: Trajectory, levels: tuple[Level, ...]
) -> dict[str, float]:
    """{startup_excess, startup_time} of `result` against `truth`: the level of largest excess among
    `levels`."""
    found = {"startup_excess": math.nan, "startup_time": math.nan}
    times = np.asarray(result.times, dtype=float)
    if len(times) < MIN_POINTS:
        return found
    length, rate = scenario.characteristic_length, characteristic_rate(scenario)
    compared = truth.select(tuple(b for b in scenario.output_bodies if b in truth.bodies))
    for level in levels:
        series = level_series(result, compared, level, length, rate)
        if series is None or not np.all(np.isfinite(series)):
            continue
        half = len(series) // 2
        steady = float(np.max(series[half:]))
        if not steady > 0.0:
            continue
        excess = float(np.max(series[:half])) / steady
        if math.isnan(found["startup_excess"]) or excess > found["startup_excess"]:
            above = np.flatnonzero(series[:half] > SETTLED * steady)
            last = float(times[above[-1]] - times[0]) if above.size else 0.0
            found = {"startup_excess": excess, "startup_time": last}
    return found
