"""Error metrics on trajectories with errors known by construction."""

from __future__ import annotations

import dataclasses
import math
import warnings

import numpy as np
import pytest

import reference_solver
from reports.scoring.metrics import (
    METRIC_COLUMNS,
    error_metrics,
    headline,
    headline_series,
    level_errors,
    residual_metrics,
    summarise,
)
from scenarios import Trajectory, build

SCENARIO = build("slider_crank")  # bodies crank, rod, slider; characteristic length 0.2


def truth() -> Trajectory:
    times = np.asarray(SCENARIO.times())
    rng = np.random.default_rng(1)
    shape = (len(times), 3, 3)
    return Trajectory(times, SCENARIO.output_bodies, *(rng.normal(size=shape) for _ in range(3)))


def perturbed(reference: Trajectory) -> tuple[Trajectory, dict[str, float]]:
    """A copy with a 3-4-5 jump of the rod at one instant and a linear drift of the crank angle."""
    t = reference.times
    position = reference.position.copy()
    position[7, 1, :2] += (3e-3, 4e-3)
    position[:, 0, 2] += 2e-4 * t
    acceleration = reference.acceleration.copy()
    acceleration[:, 2, 0] -= 0.5  # the slider's x acceleration, off by 0.5 everywhere
    result = Trajectory(t, reference.bodies, position, reference.velocity, acceleration)
    expected = {
        "position_length_max": 5e-3,
        "position_length_rms": math.sqrt(25e-6 / len(t)),
        "position_length_final": 0.0,
        "position_angle_max": 2e-4 * t[-1],
        "position_angle_rms": 2e-4 * math.sqrt(np.mean(t**2)),
        "position_angle_final": 2e-4 * t[-1],
        "velocity_length_max": 0.0,
        "velocity_angle_max": 0.0,
        "acceleration_length_max": 0.5,
        "acceleration_length_rms": 0.5,
        "acceleration_length_final": 0.5,
        "acceleration_angle_max": 0.0,
    }
    return result, expected


def test_known_errors_per_level_and_quantity() -> None:
    result, expected = perturbed(truth())
    metrics = error_metrics(SCENARIO, result, truth())
    for column, value in expected.items():
        assert metrics[column] == pytest.approx(value, rel=1e-9, abs=1e-15), column
    assert metrics["error"] == pytest.approx(max(5e-3 / 0.2, 2e-4 * result.times[-1]), rel=1e-12)


def test_body_order_and_extra_bodies_do_not_matter() -> None:
    reference = truth()
    result, expected = perturbed(reference)
    order = ("slider", "crank", "rod")
    shuffled = result.select(order)
    extra = np.zeros((len(result.times), 1, 3))
    padded = Trajectory(
        result.times,
        (*order, "ghost"),
        *(np.concatenate([shuffled.level(lv), extra + 9.0], axis=1) for lv in shuffled.levels),
    )
    metrics = error_metrics(SCENARIO, padded, reference)
    assert metrics["position_length_max"] == pytest.approx(expected["position_length_max"])
    assert metrics["acceleration_length_max"] == pytest.approx(0.5)


def test_levels_missing_or_not_asked_are_left_out() -> None:
    reference = truth()
    result, _ = perturbed(reference)
    no_velocity = dataclasses.replace(result, velocity=None)
    metrics = error_metrics(SCENARIO, no_velocity, reference)
    velocity = [c for c in METRIC_COLUMNS if c.startswith("velocity")]
    assert all(math.isnan(metrics[c]) for c in velocity)
    assert not math.isnan(metrics["acceleration_length_max"])
    positions_only = dataclasses.replace(SCENARIO, levels=("position",))
    metrics = error_metrics(positions_only, result, reference)
    assert [c for c in METRIC_COLUMNS if not math.isnan(metrics[c])] == [
        c for c in METRIC_COLUMNS if c.startswith("position")
    ]


def test_headline_series_peaks_at_the_headline() -> None:
    reference = truth()
    result, _ = perturbed(reference)
    series = headline_series(result, reference, SCENARIO.characteristic_length)
    assert series.shape == reference.times.shape
    assert series.max() == pytest.approx(error_metrics(SCENARIO, result, reference)["error"])
    assert series[7] == pytest.approx(5e-3 / 0.2)


def test_a_different_grid_is_refused() -> None:
    reference = truth()
    shifted = dataclasses.replace(reference, times=reference.times + 1e-3)
    with pytest.raises(ValueError, match="same time grid"):
        error_metrics(SCENARIO, shifted, reference)


def test_constraint_residual_sees_a_known_gap() -> None:
    """The slider moved along its axis, by up to 1e-5 at the end, opens the rod-slider pin by
    exactly that, which the residual states in units of the characteristic length (0.2)."""
    times = np.asarray(SCENARIO.times())
    solved = reference_solver.solve(SCENARIO, times, tolerance=1e-12)
    assert (
        residual_metrics(SCENARIO, solved, reference_solver.constraint_residual)["constraint_residual"]
        < 1e-11
    )
    position = solved.position.copy()
    position[:, solved.bodies.index("slider"), 0] += np.linspace(0.0, 1e-5, len(times))
    moved = dataclasses.replace(solved, position=position)
    gap = residual_metrics(SCENARIO, moved, reference_solver.constraint_residual)
    assert gap["constraint_residual"] == pytest.approx(1e-5 / 0.2, rel=1e-6)
    assert gap["constraint_residual_final"] == pytest.approx(1e-5 / 0.2, rel=1e-6)


def test_a_truth_that_stops_is_compared_where_it_exists() -> None:
    """A stress truth is NaN past a singular time: the statistics cover the times before it."""
    series = np.array([1e-9, 3e-9, 2e-9, np.nan, np.nan])
    stats = summarise(series)
    assert stats["max"] == 3e-9 and stats["final"] == 2e-9
    assert stats["rms"] == pytest.approx(np.sqrt((1 + 9 + 4) / 3) * 1e-9)
    assert all(np.isnan(v) for v in summarise(np.full(3, np.nan)).values())


def test_a_level_missing_from_either_trajectory_is_refused_by_name() -> None:
    reference = truth()
    no_velocity = dataclasses.replace(reference, velocity=None)
    for result, ref in ((no_velocity, reference), (reference, no_velocity)):
        with pytest.raises(ValueError, match=r"^level velocity is missing from one of the trajectories$"):
            level_errors(result, ref, "velocity")


def test_the_grid_and_the_bodies_must_match_exactly() -> None:
    """The grids agree to 1e-12 absolute: at t = 0 no relative slack applies, so 1e-10 is refused."""
    reference = truth()
    times = reference.times.copy()
    times[0] += 1e-10
    with pytest.raises(ValueError, match=r"^the trajectory and the reference are not on the same time grid$"):
        level_errors(dataclasses.replace(reference, times=times), reference, "position")
    with pytest.raises(ValueError, match=r"^bodies differ: \('slider', 'crank', 'rod'\) against"):
        level_errors(reference.select(("slider", "crank", "rod")), reference, "position")


def test_statistics_name_their_columns_and_an_overflow_is_infinite_silently() -> None:
    assert sorted(summarise(np.full(3, np.nan))) == ["final", "max", "rms"]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        stats = summarise(np.array([1e200, 2e200]))
    assert stats == {"max": 2e200, "rms": math.inf, "final": 2e200}


def test_the_headline_needs_both_position_quantities() -> None:
    assert headline({"position_length_max": 0.1, "position_angle_max": 0.3}, 0.2) == 0.5
    assert math.isnan(headline({"position_length_max": 0.1, "position_angle_max": math.nan}, 0.2))
    assert math.isnan(headline({"position_length_max": math.nan, "position_angle_max": 0.1}, 0.2))


def test_an_empty_residual_is_nan_under_both_names() -> None:
    empty = residual_metrics(SCENARIO, truth(), lambda scenario, result: np.empty(0))
    assert sorted(empty) == ["constraint_residual", "constraint_residual_final"]
    assert all(math.isnan(v) for v in empty.values())
