"""Driving forces against the native inverse dynamics: a known error measured exactly, Pinocchio's
dynamic modes' drive multipliers against the native torques, and the runner's row."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import adapters
from adapters.base import Setting
from reports.harness.comparison import compare
from reports.harness.driver_forces import driver_force_error, native_forces
from reports.harness.truth import independent_truth
from scenarios import load

SCENARIO = load("slider_crank", {"steps": 24})


def _native_run():
    run = adapters.load("reference").run(SCENARIO, Setting.of("newton", tolerance=1e-12, inverse_dynamics=1))
    assert run.status == "ok" and run.trajectory is not None
    return run.trajectory


def test_a_known_force_error_is_measured() -> None:
    """The native run's own torque shifted by delta at one time: the error is delta over the largest
    native torque."""
    trajectory = _native_run()
    torque = trajectory.extras["crank_drive.force"].copy()
    delta = 1e-3
    torque[5] += delta
    shifted = dataclasses.replace(trajectory, extras={"crank_drive.force": torque})
    scale = np.max(np.abs(native_forces(SCENARIO, np.asarray(SCENARIO.times()))["crank_drive.force"]))
    assert driver_force_error(SCENARIO, shifted) == pytest.approx(delta / scale, rel=1e-6)


def test_a_force_column_no_driver_gives_is_refused() -> None:
    trajectory = dataclasses.replace(_native_run(), extras={"nosuch.force": np.zeros(25)})
    with pytest.raises(KeyError, match=r"nosuch\.force"):
        driver_force_error(SCENARIO, trajectory)


@pytest.mark.parametrize("mode", ["dynamic", "baumgarte"])
def test_pinocchio_drive_multipliers_are_the_native_torques(mode: str) -> None:
    """Measured 5e-11 of the largest torque (62 N m) on the slider-crank, both modes."""
    pinocchio = adapters.load("pinocchio")
    run = pinocchio.run(SCENARIO, Setting.of(mode))
    assert run.status == "ok" and run.trajectory is not None
    assert "crank_drive.force" in run.trajectory.extras
    assert driver_force_error(SCENARIO, run.trajectory) < 1e-9
    metrics, _, _ = compare(
        SCENARIO, run, independent_truth(SCENARIO, np.asarray(SCENARIO.times())).trajectory, None
    )
    assert metrics["driver_force_error"] < 1e-9
