"""Whether a run that ended `ok` has drifted, judged from the run alone, with no truth.

A run can end `ok` and be wrong: an explicit integrator past its stability limit, soft constraints
torn apart. Two figures any user can compute from the run itself say so:
- the constraint residual (already on every row, in characteristic lengths and radians): above
  RESIDUAL_LIMIT the mechanism has come apart;
- in a conservative free-dynamics scene (no drivers, no applied loads, no damping: gravity and
  springs only), the change of T + V over the run, over its own largest kinetic energy (at least the
  energy scale of harness.energy_drift): above ENERGY_LIMIT the energy balance is broken. Where
  loads or drivers do work, the balance needs their work, which a run does not always report, and
  only the residual is used.
The limits are wide on purpose: every default run of the suites sits orders of magnitude below them
(tests/reports/harness/test_self_check.py), so a mark means a gross drift, not a setting's accuracy.
"""

from __future__ import annotations

import math

import numpy as np

from reports.harness.energy_drift import energy_scale, kinetic_energy, mechanical_energy
from scenarios.forces import AppliedForce, AppliedTorque, RotationalSpringDamper, SpringDamper
from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory

RESIDUAL_LIMIT = 1e-3
ENERGY_LIMIT = 1e-2


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
    """The largest |E(t) - E(t0)| over the run's own energy scale; NaN where T + V need not stay
    constant or the run gives no velocities."""
    if not conservative(scenario) or trajectory.velocity is None:
        return math.nan
    energy = mechanical_energy(scenario, trajectory)
    scale = max(float(np.max(kinetic_energy(scenario, trajectory))), energy_scale(scenario, trajectory))
    return float(np.max(np.abs(energy - energy[0]))) / scale


def verdict(residual: float, energy: float) -> str:
    """'' for a run with no sign of drift; else what drifted, with the figure and its limit."""
    found = []
    if math.isfinite(residual) and residual > RESIDUAL_LIMIT:
        found.append(f"constraint residual {residual:.2g} (limit {RESIDUAL_LIMIT:g})")
    if math.isfinite(energy) and energy > ENERGY_LIMIT:
        found.append(f"energy T + V changed by {energy:.2g} of its kinetic energy (limit {ENERGY_LIMIT:g})")
    if math.isinf(residual):
        found.append("constraint residual not finite")
    return "drifted: " + "; ".join(found) if found else ""


def of_trajectory(scenario: Scenario, trajectory: Trajectory) -> str:
    """The verdict for a trajectory outside the runner (`mbxval solve`): its constraint residual by
    the native constraint equations, and its own energy change."""
    from reference_solver import constraint_residual  # on first use: the native solver is slow to import

    residual = float(
        np.max(np.abs(np.asarray(constraint_residual(scenario, trajectory), dtype=float)), initial=0.0)
    )
    return verdict(residual, energy_change(scenario, trajectory))
