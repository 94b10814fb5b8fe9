"""Drake's joint reactions (the plant's reaction forces) and, where asked for, its driving force
(the PD drive's net actuation) against the Newton-Euler forces on the closed-form motion
(scenarios.newton_euler), which no engine computes. Both are the mean of the steps either side of
an output, so first order in the step like the accelerations they balance: measured error_force
6.9e-3 (slider-crank) and 1.9e-2 (four-bar) of the force scale at the default step, 7.1e-4 on the
slider-crank at a tenth of it; the driving force 3.8e-3 on the slider-crank."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("pydrake", reason="Drake is not installed (pip install -e '.[drake]')")

import scenarios
from adapters.drake import DrakeAdapter
from adapters.drake.forces import ForceReader
from reports.scoring.forces import closed_form_forces, force_errors
from scenarios.closed_form import exact

BOUNDS = {"slider_crank": 1.4e-2, "slider_crank/slider_drive": 1.1e-2, "four_bar": 4e-2}
"""error_force at the default setting (reports.scoring.forces.FORCE_DEFINITION)."""


def error_force(name: str, fraction: float = 1.0) -> float:
    adapter = DrakeAdapter()
    scenario = scenarios.build(name)
    setting = adapter.default_setting(scenario)
    result = adapter.run(scenario, setting.replace(dt=float(setting.get("dt")) * fraction))
    assert result.status == "ok" and result.trajectory is not None, result.message
    truth = closed_form_forces(scenario, exact(scenario, result.trajectory.times))
    assert truth is not None
    found = force_errors(scenario, result.trajectory, truth)
    assert found["driver_force_error"] != found["driver_force_error"]  # not given by default: NaN
    return found["error_force"]


@pytest.mark.parametrize("name", sorted(BOUNDS))
def test_forces_match_newton_euler_on_the_closed_form(name: str) -> None:
    assert error_force(name) < BOUNDS[name]


def test_forces_converge_with_the_step() -> None:
    coarse, fine = error_force("slider_crank"), error_force("slider_crank", 0.1)
    assert 6 < coarse / fine < 15, (coarse, fine)


def test_the_driving_force_is_the_drives_net_actuation() -> None:
    adapter = DrakeAdapter()
    scenario = scenarios.build("slider_crank")
    built = adapter.build(scenario, adapter.default_setting(scenario))
    built.forces = ForceReader(built.diagram, built.plan, scenario, with_driver=True)
    trajectory = adapter.simulate(built, np.asarray(scenario.times()))
    truth = closed_form_forces(scenario, exact(scenario, trajectory.times))
    assert truth is not None
    assert force_errors(scenario, trajectory, truth)["driver_force_error"] < 8e-3
