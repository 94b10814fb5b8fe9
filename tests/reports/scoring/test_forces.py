"""The force level against the force truth: known errors measured exactly, the scale rule (a
torque counted over the characteristic length), and real engines' forces at measured bounds."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import adapters
from adapters import NATIVE
from adapters.base import Setting
from reports.scoring.comparison import measure
from reports.scoring.forces import CLOSED_FORM_FORCES, NATIVE_INVERSE, force_errors, native_forces
from reports.scoring.truth import independent_truth
from scenarios import load

SCENARIO = load("slider_crank", {"steps": 24})
TIMES = np.asarray(SCENARIO.times())


@pytest.fixture(scope="module")
def native() -> dict[str, np.ndarray]:
    return native_forces(SCENARIO, TIMES)


def _scale(native: dict[str, np.ndarray]) -> float:
    """The force scale written out by hand: the largest reaction, or the torque over L."""
    reactions = max(float(np.max(np.abs(v))) for k, v in native.items() if k.endswith((".fx", ".fy")))
    torque = float(np.max(np.abs(native["crank_drive.force"])))
    return max(reactions, torque / SCENARIO.characteristic_length)


def _run(extras: dict[str, np.ndarray]):
    trajectory = independent_truth(SCENARIO, TIMES).trajectory
    return dataclasses.replace(trajectory, extras=extras)


def test_a_known_torque_error_is_measured_over_the_scale_times_length(native) -> None:
    torque = native["crank_drive.force"].copy()
    torque[5] += 1e-3
    found = force_errors(SCENARIO, _run({"crank_drive.force": torque}), native)
    expected = 1e-3 / (_scale(native) * SCENARIO.characteristic_length)
    assert found["driver_force_error"] == pytest.approx(expected, rel=1e-6)
    assert math.isnan(found["reaction_error"])
    assert found["error_force"] == found["driver_force_error"]


def test_a_known_reaction_error_is_measured_over_the_scale(native) -> None:
    fy = native["A.fy"].copy()
    fy[7] -= 0.5
    found = force_errors(SCENARIO, _run({"A.fy": fy, "A.fx": native["A.fx"]}), native)
    assert found["reaction_error"] == pytest.approx(0.5 / _scale(native), rel=1e-6)
    assert found["error_force"] == found["reaction_error"]


def test_a_zero_native_force_is_not_a_division_by_roundoff() -> None:
    """The planetary gear's drive torque is 2e-15 N m of roundoff: its error is measured over the
    reactions' scale (0.43 N), not over the roundoff."""
    scenario = load("planetary_gears", {"steps": 12})
    times = np.asarray(scenario.times())
    native = native_forces(scenario, times)
    assert np.max(np.abs(native["arm_drive.force"])) < 1e-12
    shifted = dataclasses.replace(
        independent_truth(scenario, times).trajectory,
        extras={"arm_drive.force": native["arm_drive.force"] + 1e-6},
    )
    assert force_errors(scenario, shifted, native)["driver_force_error"] < 1e-4


def test_a_force_column_the_native_solver_lacks_is_refused(native) -> None:
    with pytest.raises(KeyError, match=r"nosuch\.force"):
        force_errors(SCENARIO, _run({"nosuch.force": np.zeros(len(TIMES))}), native)


def test_the_kinematic_truth_carries_the_newton_euler_forces_named(native) -> None:
    """The closed form's forces, not the native solver's, which they agree with to rounding."""
    truth = independent_truth(SCENARIO, TIMES)
    assert truth.forces == CLOSED_FORM_FORCES
    for column, values in native.items():
        assert not np.array_equal(truth.trajectory.extras[column], values)
        np.testing.assert_allclose(truth.trajectory.extras[column], values, rtol=0, atol=1e-10 * 700)


def test_a_native_run_is_judged_only_against_a_force_truth_not_its_own() -> None:
    run = adapters.load(NATIVE).run(SCENARIO)
    assert run.trajectory is not None and "crank_drive.force" in run.trajectory.extras
    truth = independent_truth(SCENARIO, TIMES)
    judged, _, _ = measure(SCENARIO, run, truth.trajectory, None, truth.forces)
    assert judged["error_force"] < 1e-12
    own, _, note = measure(SCENARIO, run, truth.trajectory, None, NATIVE_INVERSE)
    assert "error_force" not in own
    assert f"forces not compared: the force truth is the native solver's own ({NATIVE_INVERSE})" in note


@pytest.mark.parametrize("mode", ["dynamic", "baumgarte"])
def test_pinocchio_drive_multipliers_are_the_native_torques(mode: str) -> None:
    """Measured 5e-11 of the largest torque (62 N m) on the slider-crank, both modes."""
    run = adapters.load("pinocchio").run(SCENARIO, Setting.of(mode))
    assert run.status == "ok" and run.trajectory is not None
    assert "crank_drive.force" in run.trajectory.extras
    metrics, _, _ = measure(SCENARIO, run, independent_truth(SCENARIO, TIMES).trajectory, None)
    assert metrics["driver_force_error"] < 1e-9
