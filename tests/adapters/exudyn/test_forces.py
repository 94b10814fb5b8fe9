"""Exudyn's driving forces and reactions (SensorObject Force on the driver's coordinate connector
and the revolute joints) against the native solver's, at measured bounds, t = 0 included."""

from __future__ import annotations

import numpy as np
import pytest

import adapters
from adapters.base import Setting
from reports.harness.comparison import compare
from reports.harness.forces import native_forces
from reports.harness.truth import independent_truth
from scenarios import load

EXUDYN = adapters.load("exudyn")


def _run(name: str, setting: Setting | None, overrides: dict[str, object]):
    scenario = load(name, overrides)
    times = np.asarray(scenario.times())
    run = EXUDYN.run(scenario, setting, times)
    assert run.status == "ok", run.message
    return scenario, times, run


# Measured over a whole turn: slider_crank TR2 2.1e-6, GA3 3.7e-3 (its start-up transient);
# four_bar TR2 2.7e-5, GA3 2.5e-2.
@pytest.mark.parametrize(
    ("name", "mode", "bound"), [("slider_crank", "TR2", 6e-6), ("four_bar", "TR2", 8e-5)]
)
def test_forces_match_the_native_inverse_dynamics(name: str, mode: str, bound: float) -> None:
    setting = EXUDYN.default_setting(load(name))
    scenario, times, run = _run(name, Setting.of(mode, **dict(setting.options)), {})
    metrics, _, _ = compare(scenario, run, independent_truth(scenario, times).trajectory, None)
    assert metrics["error_force"] < bound
    assert np.isfinite(metrics["driver_force_error"]) and np.isfinite(metrics["reaction_error"])


def test_the_start_s_forces_are_exudyn_s_own_not_zero() -> None:
    """Exudyn records a start it did not solve as zero force; the adapter's first step solves it."""
    scenario, times, run = _run("slider_crank", None, {"steps": 12})
    native = native_forces(scenario, times)
    assert run.trajectory is not None
    torque = run.trajectory.extras["crank_drive.force"]
    assert abs(torque[0] - native["crank_drive.force"][0]) < 1e-6 * np.max(
        np.abs(native["crank_drive.force"])
    )


def test_scaled_masses_report_no_forces() -> None:
    _, _, run = _run("slider_crank", Setting.of("GA3", mass_scale=2.0), {"steps": 4})
    assert run.trajectory is not None
    assert "crank_drive.force" not in run.trajectory.extras
