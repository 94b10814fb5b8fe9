"""Scoring an imported trajectory: a family's closed form with a known perturbation added to one
body gives exactly that error, scaled as reports.scoring.level_error scales it (lengths over L,
velocities over L w, accelerations over L w^2, angles in rad over w^k); missing bodies and levels
are left out and said, never scored as zero."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import scenarios
from reports.run.imported import score
from reports.run.trajectory_file import read_trajectory
from reports.scoring.level_error import characteristic_rate
from scenarios import Scenario, Trajectory
from scenarios.closed_form import exact


def _write(path: Path, trajectory: Trajectory, drop: tuple[str, ...] = ()) -> Path:
    frame = trajectory.to_frame().drop(columns=list(drop))
    frame.to_csv(path, index=False, float_format="%.17g")
    return path


def _perturbed(scenario: Scenario, level: str, body: str, column: int, amount: float) -> Trajectory:
    truth = exact(scenario)
    arrays = {lv: np.array(truth.level(lv)) for lv in truth.levels}
    arrays[level][:, truth.bodies.index(body), column] += amount
    return Trajectory(truth.times, truth.bodies, extras=dict(truth.extras), **arrays)  # type: ignore[arg-type]


@pytest.mark.parametrize("name", ["slider_crank", "four_bar", "slider_crank/offset"])
def test_an_offset_in_x_is_the_position_error_over_L(name: str, tmp_path: Path) -> None:
    scenario = scenarios.build(name)
    offset = 3.0e-4
    trajectory = _perturbed(scenario, "position", "rod" if "slider" in name else "coupler", 0, offset)
    scored = score(scenario, read_trajectory(_write(tmp_path / "t.csv", trajectory), scenario), "mine")
    assert scored.truth.name == "closed form"
    row = scored.row
    assert row["error_position"] == pytest.approx(offset / scenario.characteristic_length, rel=1e-9)
    assert row["error"] == row["error_position"]
    assert row["position_length_max"] == pytest.approx(offset, rel=1e-9)
    assert row["position_length_rms"] == pytest.approx(offset, rel=1e-9)  # the same at every time
    # the levels not perturbed agree with the closed form to rounding
    assert row["error_velocity"] < 1e-12 and row["error_acceleration"] < 1e-12
    assert (row["engine"], row["setting"], row["status"], row["is_default"]) == (
        "mine",
        "imported",
        "ok",
        True,
    )
    assert "imported trajectory" in row["measures"]


def test_velocity_angle_and_acceleration_perturbations_scale_by_the_rate(tmp_path: Path) -> None:
    scenario = scenarios.build("slider_crank")
    rate, length = characteristic_rate(scenario), scenario.characteristic_length
    assert rate == 50.0  # the crank's omega
    cases = [
        ("velocity", "crank", 1, 0.02, 0.02 / (length * rate)),  # vy, m/s
        ("velocity", "rod", 2, 0.5, 0.5 / rate),  # omega, rad/s
        ("acceleration", "slider", 0, 4.0, 4.0 / (length * rate**2)),  # ax, m/s^2
        ("position", "crank", 2, 1e-3, 1e-3),  # theta, rad
    ]
    for level, body, column, amount, expected in cases:
        trajectory = _perturbed(scenario, level, body, column, amount)
        path = _write(tmp_path / f"{level}{column}.csv", trajectory)
        row = score(scenario, read_trajectory(path, scenario), "mine").row
        assert row[f"error_{level}"] == pytest.approx(expected, rel=1e-9), (level, body, column)


def test_a_perturbation_at_one_time_is_the_max_not_the_final(tmp_path: Path) -> None:
    scenario = scenarios.build("four_bar")
    truth = exact(scenario)
    position = np.array(truth.position)
    k = len(truth.times) // 3
    position[k, truth.bodies.index("rocker"), 1] += 2e-3
    trajectory = Trajectory(truth.times, truth.bodies, position=position)
    row = score(scenario, read_trajectory(_write(tmp_path / "t.csv", trajectory), scenario), "mine").row
    assert row["position_length_max"] == pytest.approx(2e-3, rel=1e-9)
    assert row["position_length_final"] < 1e-12
    assert row["position_length_rms"] == pytest.approx(2e-3 / math.sqrt(len(truth.times)), rel=1e-6)


def test_missing_levels_and_bodies_are_left_out_and_said(tmp_path: Path) -> None:
    scenario = scenarios.build("slider_crank")
    trajectory = _perturbed(scenario, "position", "slider", 0, 1e-3)
    drop = tuple(c for c in trajectory.to_frame().columns if c.startswith("crank.") or c[-2:] in ("vx", "vy"))
    drop += tuple(c for c in trajectory.to_frame().columns if c.endswith((".omega", ".ax", ".ay", ".alpha")))
    imported = read_trajectory(_write(tmp_path / "t.csv", trajectory, drop), scenario)
    assert imported.trajectory.bodies == ("rod", "slider")
    assert imported.missing_bodies == ("crank",)
    assert imported.missing_levels == ("velocity", "acceleration")
    scored = score(scenario, imported, "mine")
    row = scored.row
    assert row["error_position"] == pytest.approx(1e-3 / scenario.characteristic_length, rel=1e-9)
    assert math.isnan(row["error_velocity"]) and math.isnan(row["error_acceleration"])
    assert row["levels"] == "position"
    assert "bodies not in the file, not scored: crank" in row["message"]
    assert "velocity not in the file" in row["message"] and "acceleration not in the file" in row["message"]


def test_a_body_missing_a_level_drops_the_level_for_all(tmp_path: Path) -> None:
    scenario = scenarios.build("slider_crank")
    trajectory = exact(scenario)
    drop = ("rod.vx", "rod.vy", "rod.omega")
    imported = read_trajectory(_write(tmp_path / "t.csv", trajectory, drop), scenario)
    assert imported.trajectory.levels == ("position", "acceleration")
    assert any("velocity not in the file for rod" in n for n in imported.notes)


def test_a_dynamic_family_is_scored_against_the_native_dynamics(tmp_path: Path) -> None:
    """No closed form: the truth is the native forward dynamics at rtol 1e-13, as in a run."""
    scenario = scenarios.build("compound_pendulum/small_oscillation", overrides={"steps": 20, "t_end": 0.5})
    from reports.scoring.truth import independent_truth

    truth = independent_truth(scenario, np.asarray(scenario.times()))
    position = np.array(truth.trajectory.position)
    position[:, 0, 0] += 1e-5
    moved = Trajectory(truth.trajectory.times, truth.trajectory.bodies, position=position)
    scored = score(scenario, read_trajectory(_write(tmp_path / "t.csv", moved), scenario), "mine")
    assert scored.truth.name.startswith("native dynamics")
    assert scored.row["error_position"] == pytest.approx(1e-5 / scenario.characteristic_length, rel=1e-6)


def test_an_engines_extra_columns_are_kept_not_scored(tmp_path: Path) -> None:
    """A native dynamic run's CSV carries joint reactions (`slot.fx`) and energies (`energy.kinetic`):
    accepted as extras named after the scenario's own joints, not scored; an unknown one is refused."""
    from reports.run.trajectory_file import TrajectoryFileError
    from reports.scoring.truth import independent_truth
    from scenarios.files import read_scenario

    examples = Path(__file__).resolve().parents[3] / "examples"
    scenario = read_scenario(examples / "damped_oscillators.toml", {"steps": "10", "t_end": "0.2"})
    truth = independent_truth(scenario, np.asarray(scenario.times())).trajectory
    assert {"slot.fx", "pin.fy", "energy.kinetic"} <= set(truth.extras)
    path = _write(tmp_path / "t.csv", truth)
    imported = read_trajectory(path, scenario)
    assert set(imported.trajectory.extras) == set(truth.extras)
    assert score(scenario, imported, "mine").row["error_position"] == 0.0
    frame = truth.to_frame().assign(**{"slott.fx": 1.0})
    frame.to_csv(tmp_path / "bad.csv", index=False)
    place = len(frame.columns)  # the added column, named by its place: a message quotes no header
    unknown = rf"line 1, column {place}: not a column name of {scenario.name} \(did you mean 'slot.fx'\?\)"
    with pytest.raises(TrajectoryFileError, match=unknown):
        read_trajectory(tmp_path / "bad.csv", scenario)
