"""MuJoCo's driving forces (efc_force of the drive equalities) and joint reactions (cfrc_int of
tree joints, efc_force of loop connects) against the native solver's, at measured bounds."""

from __future__ import annotations

import numpy as np
import pytest

import adapters
from adapters.mujoco.settings import own_regulariser
from reports.scoring.comparison import measure
from reports.scoring.truth import independent_truth
from scenarios import load
from tests.support.bounds import held
from tests.support.measured import MUJOCO_FORCES

MUJOCO = adapters.load("mujoco")


def _force_metrics(name: str, own: bool) -> dict[str, float]:
    scenario = load(name)
    times = np.asarray(scenario.times())
    setting = MUJOCO.default_setting(scenario)
    if own:
        setting = own_regulariser(setting)
        assert setting in MUJOCO.ladder(scenario)
    run = MUJOCO.run(scenario, setting, times)
    assert run.status == "ok", run.message
    metrics, _, note = measure(scenario, run, independent_truth(scenario, times).trajectory, None)
    assert "forces not compared" not in note
    return metrics


@pytest.mark.parametrize("name", list(MUJOCO_FORCES))
def test_driver_forces_and_reactions_match_the_native_inverse_dynamics(name: str) -> None:
    metrics = _force_metrics(name, own=False)
    assert np.isfinite(metrics["driver_force_error"]) and np.isfinite(metrics["reaction_error"])
    own = _force_metrics(name, own=True)["error_force"]  # the regulariser's sag and the mode's error
    held([metrics["error_force"], own], MUJOCO_FORCES[name], ("default", "MuJoCo's own regulariser"))


def test_reactions_in_free_dynamics_match_the_native_multipliers() -> None:
    """four_bar_gravity over 0.2 s at the default setting."""
    scenario = load("four_bar_gravity", {"t_end": 0.2, "steps": 40})
    times = np.asarray(scenario.times())
    run = MUJOCO.run(scenario, None, times)
    assert run.status == "ok"
    metrics, _, _ = measure(scenario, run, independent_truth(scenario, times).trajectory, None)
    assert metrics["reaction_error"] < 3e-4


def test_a_cam_model_reports_no_forces() -> None:
    """The linkage adds a link of mass, the contact a preload spring: their forces are the model's,
    and the row's warnings say so."""
    scenario = load("cam_roller", {"steps": 8})
    run = MUJOCO.run(scenario, None, np.asarray(scenario.times()))
    assert run.status == "ok" and run.trajectory is not None
    assert not [c for c in run.trajectory.extras if c.endswith((".force", ".fx", ".fy"))]
    assert any("forces not given: a cam's MuJoCo model" in w for w in run.warnings), run.warnings
