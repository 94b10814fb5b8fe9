"""Error metrics of one trajectory against the reference trajectory on the same grid.

Per analysis level (position, velocity, acceleration), lengths and angles apart:
    length error at time t   max over output bodies of |Δ(x, y)| (Euclidean, in m, m/s or m/s²)
    angle error at time t    max over output bodies of |Δθ| (rad, rad/s or rad/s²)
and over the grid: `max`, `rms` (root mean square over times of the per-time error above) and
`final` (at the last grid time). A level the scenario does not ask for, or that either trajectory
lacks, is left out (NaN in the table), never filled with zeros.

The headline error, the one number of the work-precision plot and the status matrix, is
HEADLINE_DEFINITION below.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from scenarios.scenario import LEVELS, Level, Scenario
from scenarios.trajectory import Trajectory

QUANTITIES = ("length", "angle")
STATISTICS = ("max", "rms", "final")
METRIC_COLUMNS: tuple[str, ...] = tuple(
    f"{level}_{quantity}_{stat}" for level in LEVELS for quantity in QUANTITIES for stat in STATISTICS
)
HEADLINE_DEFINITION = (
    "error = the largest position-level error over the time grid and the output bodies: "
    "position errors |Δ(x, y)| divided by the scenario's characteristic length, angle errors |Δθ| in "
    "radians, whichever is larger (dimensionless)."
)

Residual = Callable[[Scenario, Trajectory], np.ndarray]


def compared_levels(scenario: Scenario, result: Trajectory, truth: Trajectory) -> tuple[Level, ...]:
    """The levels the scenario asks for and both trajectories have."""
    return tuple(lv for lv in scenario.levels if lv in result.levels and lv in truth.levels)


def level_errors(result: Trajectory, truth: Trajectory, level: Level) -> tuple[np.ndarray, np.ndarray]:
    """Per-time (length error, angle error) at `level`, each of shape (len(times),)."""
    _check_grid(result, truth)
    return _level_differences(result, truth, level)


def _level_differences(result: Trajectory, truth: Trajectory, level: Level) -> tuple[np.ndarray, np.ndarray]:
    """`level_errors` on a grid already checked."""
    mine, ref = result.level(level), truth.level(level)
    if mine is None or ref is None:
        raise ValueError(f"level {level} is missing from one of the trajectories")
    diff = mine - ref
    lengths = np.hypot(diff[:, :, 0], diff[:, :, 1]).max(axis=1)
    angles = np.abs(diff[:, :, 2]).max(axis=1)
    return lengths, angles


def summarise(series: np.ndarray) -> dict[str, float]:
    """max, rms and final value of a per-time error series, over the times where it is defined: a
    stress truth stops (NaN) where no configuration exists past a singular time. An engine's own
    non-finite values never get here (its run is `diverged`); an error that overflows counts, as
    infinite."""
    defined = series[~np.isnan(series)]
    if defined.size == 0:
        return dict.fromkeys(("max", "rms", "final"), math.nan)
    with np.errstate(over="ignore"):
        rms = float(np.sqrt(np.mean(defined**2)))
    return {"max": float(np.max(defined)), "rms": rms, "final": float(defined[-1])}


def error_metrics(scenario: Scenario, result: Trajectory, truth: Trajectory) -> dict[str, float]:
    """Every metric column (NaN for the levels left out) and the headline `error`."""
    bodies = scenario.output_bodies
    result, truth = result.select(bodies), truth.select(bodies)
    metrics = dict.fromkeys(METRIC_COLUMNS, math.nan)
    levels = compared_levels(scenario, result, truth)
    if levels:
        _check_grid(result, truth)  # once for every level (a tenth of a millisecond a check)
    for level in levels:
        lengths, angles = _level_differences(result, truth, level)
        for quantity, series in zip(QUANTITIES, (lengths, angles), strict=True):
            for stat, value in summarise(series).items():
                metrics[f"{level}_{quantity}_{stat}"] = value
    metrics["error"] = headline(metrics, scenario.characteristic_length)
    return metrics


def headline(metrics: dict[str, float], characteristic_length: float) -> float:
    """HEADLINE_DEFINITION from the metric columns (NaN when positions were not compared)."""
    length, angle = metrics["position_length_max"], metrics["position_angle_max"]
    if math.isnan(length) or math.isnan(angle):
        return math.nan
    return max(length / characteristic_length, angle)


def headline_series(result: Trajectory, truth: Trajectory, characteristic_length: float) -> np.ndarray:
    """The headline error at each grid time over the truth's bodies (its maximum is the headline)."""
    lengths, angles = level_errors(result.select(truth.bodies), truth, "position")
    return np.maximum(lengths / characteristic_length, angles)


def residual_metrics(scenario: Scenario, result: Trajectory, residual: Residual) -> dict[str, float]:
    """The largest constraint residual |C| over the grid and the one at its last time, its drift
    (the reference's residual states lengths in units of the characteristic length, angles in
    radians)."""
    values = np.abs(np.asarray(residual(scenario, result), dtype=float))
    if not values.size:
        return {"constraint_residual": math.nan, "constraint_residual_final": math.nan}
    return {"constraint_residual": float(np.max(values)), "constraint_residual_final": float(values[-1])}


def _check_grid(result: Trajectory, truth: Trajectory) -> None:
    if len(result.times) != len(truth.times) or not np.allclose(result.times, truth.times, atol=1e-12):
        raise ValueError("the trajectory and the reference are not on the same time grid")
    if result.bodies != truth.bodies:
        raise ValueError(f"bodies differ: {result.bodies} against {truth.bodies}")
