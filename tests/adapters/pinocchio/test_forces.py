"""Pinocchio's driving forces and joint reactions (adapters.pinocchio.forces) in every mode, against
the force truth: Newton-Euler on the closed form for the driven families, the native dynamics'
multipliers in free dynamics."""

from __future__ import annotations

import numpy as np
import pytest

from adapters.pinocchio import PinocchioAdapter
from reports.scoring.forces import CLOSED_FORM_FORCES, NATIVE_MULTIPLIERS, force_columns, force_errors
from reports.scoring.truth import independent_truth
from scenarios.registry import build

ADAPTER = PinocchioAdapter()


def _errors(name: str, mode: str | None) -> tuple[dict[str, float], str, int]:
    scenario = build(name)
    times = np.asarray(scenario.times())
    setting = ADAPTER.default_setting(scenario) if mode is None else ADAPTER.free_setting(scenario, mode)
    run = ADAPTER.simulate(ADAPTER.build(scenario, setting), times)
    truth = independent_truth(scenario, times)
    forces = {c: truth.trajectory.extras[c] for c in force_columns(truth.trajectory)}
    return force_errors(scenario, run, forces), truth.forces, len(force_columns(run))


@pytest.mark.parametrize(
    ("name", "mode", "bound"),
    [
        ("slider_crank", None, 1e-13),
        ("slider_crank/slider_drive", None, 1e-13),
        ("four_bar", None, 1e-13),
        ("slider_crank", "dynamic", 1e-9),
        ("four_bar", "dynamic", 1e-8),
    ],
)
def test_driven_forces_meet_the_newton_euler_truth(name: str, mode: str | None, bound: float) -> None:
    errors, truth, count = _errors(name, mode)
    assert truth == CLOSED_FORM_FORCES
    assert count == 9  # the driver and four joints' (fx, fy)
    assert errors["driver_force_error"] < bound and errors["reaction_error"] < bound


@pytest.mark.parametrize(
    ("name", "count"), [("four_bar_gravity", 8), ("andrews_squeezer", 20), ("compound_pendulum", 4)]
)
def test_free_dynamics_reactions_meet_the_native_multipliers(name: str, count: int) -> None:
    """Gravity, and Andrews' spring and motor torque, passed to rnea as the loads they are; a tree
    with no rows (the compound pendulum) has its joints' reactions alone."""
    errors, truth, columns = _errors(name, None)
    assert truth == NATIVE_MULTIPLIERS and columns == count
    assert errors["reaction_error"] < 1e-7


@pytest.mark.parametrize("mode", ["kinematic", "dynamic"])
def test_gear_rows_carry_the_planetary_forces(mode: str) -> None:
    """Gears as coupling rows (kinematic `gears=row`, and every dynamic mode): their multiplier acts
    on the gears' angles as the gear law; the driver's torque and the pivots' reactions meet the
    Newton-Euler truth (measured 5e-15 and 1e-13)."""
    scenario = build("planetary_gears")
    times = np.asarray(scenario.times())
    if mode == "kinematic":
        setting = ADAPTER.default_setting(scenario).replace(gears="row")
    else:
        setting = ADAPTER.free_setting(scenario, mode)
    run = ADAPTER.simulate(ADAPTER.build(scenario, setting), times)
    truth = independent_truth(scenario, times)
    assert truth.forces == CLOSED_FORM_FORCES and len(force_columns(run)) == 5
    forces = {c: truth.trajectory.extras[c] for c in force_columns(truth.trajectory)}
    assert force_errors(scenario, run, forces)["error_force"] < 1e-11


def test_a_force_it_cannot_give_is_named() -> None:
    scenario = build("spur_gears")
    with pytest.warns(UserWarning, match="forces not given: a gear as a mimic joint"):
        ADAPTER.build(scenario, ADAPTER.default_setting(scenario))


def test_the_loop_forces_are_constraint_dynamics_own_multipliers() -> None:
    """In the dynamic modes the least-squares multipliers of J^T mu = rnea - tau are the forces
    constraintDynamics applied: data.lambda_c is the force on the closing joint's first side (here
    the ground at O4), so the rocker's reaction is its opposite."""
    scenario = build("four_bar_gravity")
    times = np.asarray(scenario.times())[:6]
    built = ADAPTER.build(scenario, ADAPTER.default_setting(scenario))
    run = ADAPTER.simulate(built, times)
    nq = built.pm.model.nq
    assert built.dynamics is not None and built.start is not None
    q, v, _, _ = built.dynamics.run(built.start[1][:nq], built.start[2][:nq], times)
    for k in range(1, len(times)):
        built.dynamics.acceleration(float(times[k]), q[k], v[k])
        applied = np.asarray(built.dynamics.data.lambda_c)[:2]
        reported = np.array([run.extras["O4.fx"][k], run.extras["O4.fy"][k]])
        np.testing.assert_allclose(reported, -applied, rtol=0, atol=1e-9 * np.max(np.abs(applied)))
