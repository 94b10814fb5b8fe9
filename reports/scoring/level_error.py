"""The dimensionless error of a run at each analysis level, comparable across scenarios and scales.

Each scenario has a characteristic length L (its own declaration) and a characteristic rate w: the
driver's speed |omega| (the crank, the input gear, the cam, the arm, the pinion), or for an oscillating
driver its angular frequency |omega|. Every quantity of a mechanism driven at w scales with it:

    position      lengths / L          angles in rad
    velocity      speeds / (L w)       rates / w
    acceleration  accelerations / (L w^2)   angular accelerations / w^2

The error at a level is the largest of these over the grid and the output bodies (the Euclidean norm
of the (x, y) difference for lengths, |dtheta| for angles). A level a trajectory does not carry, or
the scenario does not ask for, is NaN, never zero. A scenario without an `omega` parameter takes one
cycle over its time span, w = 2 pi / t_end.
"""

from __future__ import annotations

import math

import numpy as np

from scenarios.scenario import LEVELS, Level, Scenario, characteristic_rate
from scenarios.trajectory import Trajectory

LEVEL_COLUMNS: dict[Level, str] = {level: f"error_{level}" for level in LEVELS}
RATE_POWER: dict[Level, int] = {"position": 0, "velocity": 1, "acceleration": 2}
SCALE_DEFINITION = (
    "Errors are dimensionless, the largest over the grid and the output bodies, per level: lengths "
    "over the characteristic length L, velocities over L·ω, accelerations over L·ω²; angles in rad, "
    "angular rates over ω, angular accelerations over ω², where ω is the characteristic rate: the "
    "driver's |ω| (crank, input gear, cam, planet arm, pinion; the angular frequency of an "
    "oscillating driver). `error` is the position level."
)


def level_scales(length: float, rate: float, level: Level) -> tuple[float, float]:
    """(length scale, angle scale) dividing the differences at `level`."""
    power = RATE_POWER[level]
    return length * rate**power, rate**power


def level_series(
    result: Trajectory, truth: Trajectory, level: Level, length: float, rate: float
) -> np.ndarray | None:
    """The dimensionless error at each grid time (NaN where the truth is undefined), or None when
    either trajectory lacks the level."""
    mine, ref = result.select(truth.bodies).level(level), truth.level(level)
    if mine is None or ref is None:
        return None
    if mine.shape != ref.shape:
        raise ValueError(f"{level}: shapes differ, {mine.shape} against {ref.shape}")
    length_scale, angle_scale = level_scales(length, rate, level)
    with np.errstate(over="ignore"):  # an overflow is an infinite error, counted as one
        diff = mine - ref
        lengths = np.hypot(diff[:, :, 0], diff[:, :, 1]) / length_scale
        angles = np.abs(diff[:, :, 2]) / angle_scale
    return np.asarray(np.fmax(lengths, angles).max(axis=1), dtype=float)


def largest(series: np.ndarray | None) -> float:
    """The largest defined value of a series (an infinite error, from an overflow, counts); NaN
    when none is defined (NaN is where the truth has no value)."""
    if series is None:
        return math.nan
    defined = series[~np.isnan(series)]
    return float(defined.max()) if defined.size else math.nan


def level_errors(
    scenario: Scenario, result: Trajectory, truth: Trajectory, levels: tuple[Level, ...] | None = None
) -> dict[str, float]:
    """{error_position, error_velocity, error_acceleration}: NaN for a level not compared."""
    asked = scenario.levels if levels is None else levels
    truth = truth.select(tuple(b for b in scenario.output_bodies if b in truth.bodies))
    length, rate = scenario.characteristic_length, characteristic_rate(scenario)
    out = dict.fromkeys(LEVEL_COLUMNS.values(), math.nan)
    for level in asked:
        out[LEVEL_COLUMNS[level]] = largest(level_series(result, truth, level, length, rate))
    return out
