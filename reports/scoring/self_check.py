"""Whether a run that ended `ok` has drifted, judged from the run alone, with no truth.

A run can end `ok` and be wrong: an explicit integrator past its stability limit, soft constraints
torn apart. Two figures any user can compute from the run itself say so:
- the constraint residual (already on every row, in characteristic lengths and radians): above
  RESIDUAL_LIMIT the mechanism has come apart;
- its energy balance: the change of T + V over the run less the work done on it since the start
  (applied loads' power, dampers' dissipation, and the drivers' power from the driving forces the
  run reports, each integrated over the grid by the trapezoidal rule with the run's own
  accelerations as end slopes where the power's rate is known), over its own largest kinetic
  energy or work (at least the energy scale of scoring.energy_drift): above ENERGY_LIMIT the
  balance is broken. A driven run that reports no driving force has no balance (NaN);
- step halving (Erez, Tassa and Todorov 2015 compare engines this way): the largest difference in
  positions (characteristic lengths, radians) between the run and the same setting at half its step
  `dt`; above STEP_LIMIT the run has not converged in its step. It costs a second run, about twice
  the first, so it is made only where there is no truth to judge the run: `mbxval solve`, and the
  runner's rows whose truth could not be made (run.group_runs).
The limits are wide on purpose: the default runs of the suites sit orders of magnitude below them,
a first-order engine's a few times below (tests/reports/scoring/test_self_check.py), so a mark
means a gross drift, not a setting's accuracy.
"""

from __future__ import annotations

import math

import numpy as np

from adapters.base import Adapter, Setting
from reports.scoring.energy_drift import energy_scale, kinetic_energy, mechanical_energy
from reports.scoring.level_error import level_errors
from reports.scoring.work import work
from scenarios.forces import AppliedForce, AppliedTorque, RotationalSpringDamper, SpringDamper
from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory

RESIDUAL_LIMIT = 1e-3
ENERGY_LIMIT = 1e-2
STEP_LIMIT = 1e-2
HALVABLE_TIMES = 5
"""The fewest grid times on which the work's quadrature error is estimated by integrating over every
other time (three or more): on fewer a run that has work done on it is not judged by its energy."""


def conservative(scenario: Scenario) -> bool:
    """Free dynamics whose only loads are gravity and undamped springs: T + V stays constant."""
    if scenario.analysis != "dynamic" or scenario.drivers:
        return False
    for force in scenario.forces:
        if isinstance(force, AppliedForce | AppliedTorque):
            return False
        if isinstance(force, SpringDamper | RotationalSpringDamper) and force.damping != 0.0:
            return False
    return True


def energy_change(scenario: Scenario, trajectory: Trajectory) -> float:
    """The largest |E(t) - E(t0) - W(t)| over the run's own energy scale, W the work done on the
    mechanism since t0 (scoring.work), less what the grid's quadrature of W cannot tell apart (the
    largest change of W when it is integrated over every other grid time instead): a coarse grid
    does not make an exact run look drifted. NaN where the run gives no velocities, drives the
    mechanism without reporting its driving forces, or has work done on it over a grid too short
    to halve (under HALVABLE_TIMES times: not judged)."""
    if trajectory.velocity is None or not any(body.mass or body.inertia for body in scenario.bodies):
        return math.nan
    done = work(scenario, trajectory)
    if done is None:
        return math.nan
    energy = mechanical_energy(scenario, trajectory)
    scale = max(
        float(np.max(kinetic_energy(scenario, trajectory))),
        float(np.max(np.abs(done))),
        energy_scale(scenario, trajectory),
    )
    imbalance = float(np.max(np.abs(energy - energy[0] - done)))
    if not np.any(done):
        return imbalance / scale  # no work done, no quadrature to doubt
    if len(trajectory.times) < HALVABLE_TIMES:
        return math.nan  # the quadrature's error cannot be estimated: not judged, never a drift
    return max(imbalance - _quadrature_uncertainty(scenario, trajectory, done), 0.0) / scale


def _quadrature_uncertainty(scenario: Scenario, trajectory: Trajectory, done: np.ndarray) -> float:
    """The largest difference of the work at the common times when it is integrated over every other
    grid time: an upper estimate of the quadrature's own error on the full grid."""
    coarse = work(scenario, _every_other(trajectory))
    return 0.0 if coarse is None else float(np.max(np.abs(coarse - done[::2])))


def _every_other(trajectory: Trajectory) -> Trajectory:
    """The trajectory at its even grid times."""

    def half(level: np.ndarray | None) -> np.ndarray | None:
        return None if level is None else level[::2]

    return Trajectory(
        trajectory.times[::2],
        trajectory.bodies,
        half(trajectory.position),
        half(trajectory.velocity),
        half(trajectory.acceleration),
        {name: values[::2] for name, values in trajectory.extras.items()},
    )


def step_halving(
    adapter: Adapter, scenario: Scenario, setting: Setting, times: np.ndarray, trajectory: Trajectory
) -> float:
    """The largest position difference between `trajectory` and the same setting's run at half its
    step, in characteristic lengths and radians; NaN where the setting has no step `dt`, infinite
    where the halved run is not ok (a step that only works at that size is no converged one)."""
    step = setting.get("dt")
    if step is None:
        return math.nan
    half = adapter.run(scenario, setting.replace(dt=float(step) / 2.0), times)
    if half.status != "ok" or half.trajectory is None:
        return math.inf
    return level_errors(scenario, trajectory, half.trajectory, ("position",))["error_position"]


def verdict(residual: float, energy: float, halving: float = math.nan) -> str:
    """'' for a run with no sign of drift; else what drifted, with the figure and its limit."""
    found = []
    if math.isfinite(residual) and residual > RESIDUAL_LIMIT:
        found.append(f"constraint residual {residual:.2g} (limit {RESIDUAL_LIMIT:g})")
    if math.isfinite(energy) and energy > ENERGY_LIMIT:
        found.append(
            f"energy T + V changed by {energy:.2g} of its energy scale beyond the work done on it "
            f"(limit {ENERGY_LIMIT:g})"
        )
    if halving > STEP_LIMIT:
        found.append(f"positions moved by {halving:.2g} at half the step (limit {STEP_LIMIT:g})")
    if math.isinf(residual):
        found.append("constraint residual not finite")
    return "drifted: " + "; ".join(found) if found else ""


def of_trajectory(scenario: Scenario, trajectory: Trajectory, halving: float = math.nan) -> str:
    """The verdict for a trajectory outside the runner (`mbxval solve`): its constraint residual by
    the native constraint equations, its own energy balance, and its step halving where made."""
    from reference_solver import constraint_residual  # on first use: the native solver is slow to import

    residual = float(
        np.max(np.abs(np.asarray(constraint_residual(scenario, trajectory, None), dtype=float)), initial=0.0)
    )
    return verdict(residual, energy_change(scenario, trajectory), halving)
