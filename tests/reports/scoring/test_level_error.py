"""Per-level dimensionless errors on hand-made trajectories whose errors are known by construction."""

from __future__ import annotations

import dataclasses
import math
import warnings

import numpy as np
import pytest

import scenarios
from reports.scoring.level_error import characteristic_rate, largest, level_errors, level_series
from tests.support.fake_engine import fake_truth


def present(values: np.ndarray | None) -> np.ndarray:
    """A copy of a level the fake truth always has."""
    assert values is not None
    return values.copy()


def test_known_offsets_at_each_level_and_a_missing_level() -> None:
    scenario = scenarios.build("slider_crank")  # omega 50 rad/s
    length, rate = scenario.characteristic_length, 50.0
    assert characteristic_rate(scenario) == rate
    times = np.asarray(scenario.times())
    truth = fake_truth(scenario, times)
    position, velocity = present(truth.position), present(truth.velocity)
    position[7, 1, 1] += 3e-4  # 3e-4 m in y on one body at one time
    velocity[:, 0, 2] += 0.5  # 0.5 rad/s on every rate of the first body
    run = dataclasses.replace(truth, position=position, velocity=velocity, acceleration=None)
    errors = level_errors(scenario, run, truth)
    assert errors["error_position"] == pytest.approx(3e-4 / length, rel=1e-9)
    assert errors["error_velocity"] == pytest.approx(0.5 / rate, rel=1e-9)
    assert math.isnan(errors["error_acceleration"])  # not produced: NaN, never zero


def test_acceleration_lengths_scale_with_rate_squared() -> None:
    scenario = scenarios.build("four_bar")
    truth = fake_truth(scenario, np.asarray(scenario.times()))
    acceleration = present(truth.acceleration)
    acceleration[:, 0, 0] += 2.0  # 2 m/s^2 in x
    run = dataclasses.replace(truth, acceleration=acceleration)
    rate = float(scenario.parameter("omega"))
    errors = level_errors(scenario, run, truth)
    assert errors["error_position"] == 0.0 and errors["error_velocity"] == 0.0
    assert errors["error_acceleration"] == pytest.approx(2.0 / (scenario.characteristic_length * rate**2))


def test_undefined_truth_times_are_not_scored() -> None:
    scenario = scenarios.build("spur_gears")
    truth = fake_truth(scenario, np.asarray(scenario.times()))
    cut = present(truth.position)
    cut[10:] = np.nan  # no truth past a singular time
    run_position = present(truth.position)
    run_position[20:, 0, 2] += 1.0  # wrong only where no truth exists
    run_position[3, 0, 2] += 1e-6
    errors = level_errors(
        scenario, dataclasses.replace(truth, position=run_position), dataclasses.replace(truth, position=cut)
    )
    assert errors["error_position"] == pytest.approx(1e-6)


def test_levels_not_asked_are_nan_even_when_both_trajectories_carry_them() -> None:
    scenario = scenarios.build("slider_crank")
    truth = fake_truth(scenario, np.asarray(scenario.times()))
    velocity = present(truth.velocity)
    velocity[:, 0, 2] += 0.5
    errors = level_errors(
        scenario, dataclasses.replace(truth, velocity=velocity), truth, levels=("position",)
    )
    assert errors["error_position"] == 0.0
    assert math.isnan(errors["error_velocity"]) and math.isnan(errors["error_acceleration"])


def test_no_defined_time_is_nan_and_a_shape_mismatch_is_refused_by_name() -> None:
    assert math.isnan(largest(np.full(4, np.nan)))
    assert math.isnan(largest(None))
    scenario = scenarios.build("slider_crank")
    truth = fake_truth(scenario, np.asarray(scenario.times()))
    short = fake_truth(scenario, np.asarray(scenario.times())[:5])
    with pytest.raises(ValueError, match=r"^position: shapes differ, \(5, 3, 3\) against \("):
        level_series(short, truth, "position", 0.2, 50.0)


def test_an_overflowing_difference_is_an_infinite_error_without_a_warning() -> None:
    scenario = scenarios.build("slider_crank")
    truth = fake_truth(scenario, np.asarray(scenario.times()))
    position = present(truth.position)
    position[3, 0, 0], position[3, 0, 2] = 1.5e308, 1.5e308
    far = dataclasses.replace(truth, position=-position)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        series = level_series(dataclasses.replace(truth, position=position), far, "position", 0.2, 50.0)
    assert series is not None and series[3] == math.inf
