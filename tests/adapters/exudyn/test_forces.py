"""Exudyn's driving forces and reactions (SensorObject Force on the driver's coordinate connector
and the revolute joints) against the native solver's, at measured bounds, t = 0 included."""

from __future__ import annotations

import numpy as np
import pytest

import adapters
from adapters.base import Setting
from reports.harness.comparison import measure
from reports.harness.forces import native_forces
from reports.harness.truth import independent_truth
from scenarios import load
from tests.support.bounds import held

EXUDYN = adapters.load("exudyn")


def _run(name: str, setting: Setting | None, overrides: dict[str, object]):
    scenario = load(name, overrides)
    times = np.asarray(scenario.times())
    run = EXUDYN.run(scenario, setting, times)
    assert run.status == "ok", run.message
    return scenario, times, run


MEASURED: dict[tuple[str, str], float] = {
    ("slider_crank", "TR2"): 2.0e-6,
    ("slider_crank", "GA3"): 3.7e-3,  # generalized-alpha's start-up transient
    ("four_bar", "TR2"): 2.7e-5,
    ("four_bar", "GA3"): 2.5e-2,
}
"""(scenario, mode at the default step): the force error over a whole turn, measured 2026-11-25,
held two-sided (tests.support.bounds)."""


@pytest.mark.parametrize(("name", "mode"), list(MEASURED))
def test_forces_match_the_native_inverse_dynamics(name: str, mode: str) -> None:
    setting = EXUDYN.default_setting(load(name))
    scenario, times, run = _run(name, Setting.of(mode, **dict(setting.options)), {})
    metrics, _, _ = measure(scenario, run, independent_truth(scenario, times).trajectory, None)
    held([metrics["error_force"]], [MEASURED[(name, mode)]], ("force",))
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
