"""Driving forces of a run against the native inverse dynamics.

A run of a driven (kinematic) scenario whose trajectory carries its drivers' forces, in the
canonical columns `<driver>.force` (`<driver>.x.force`, `<driver>.y.force` for a point's two rows),
is compared with the forces the native solver's inverse dynamics needs to drive the same motion
(reference_solver.dynamics.inverse_dynamics on its own kinematic analysis at tolerance 1e-12):
FORCE_DEFINITION says how.
"""

from __future__ import annotations

import math

import numpy as np

from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory

SUFFIX = ".force"
FORCE_DEFINITION = (
    "driver force error = the largest |F - F_native| over the drivers and the grid, divided by the "
    "largest |F_native| (absolute, in N or N m, where the native forces are all zero)"
)


def force_columns(result: Trajectory) -> list[str]:
    """The driver-force columns the run carries."""
    return [c for c in result.extras if c.endswith(SUFFIX)]


def native_forces(scenario: Scenario, times: np.ndarray) -> dict[str, np.ndarray]:
    """Every driver's force from the native inverse dynamics on `times`."""
    from reference_solver import analyse  # on first use: the native solver is slow to import
    from reference_solver.dynamics import inverse_dynamics

    found = inverse_dynamics(scenario, analyse(scenario, times, tolerance=1e-12))
    return {k: v for k, v in found.items() if k.endswith(SUFFIX)}


def driver_force_error(scenario: Scenario, result: Trajectory) -> float:
    """FORCE_DEFINITION for a run's force columns (NaN if it has none); KeyError naming a column the
    native drivers do not have."""
    columns = force_columns(result)
    if not columns:
        return math.nan
    native = native_forces(scenario, np.asarray(result.times, dtype=float))
    unknown = [c for c in columns if c not in native]
    if unknown:
        raise KeyError(f"no driver gives {', '.join(unknown)} (known: {', '.join(native)})")
    worst = max(float(np.max(np.abs(result.extras[c] - native[c]))) for c in columns)
    scale = max(float(np.max(np.abs(native[c]))) for c in columns)
    return worst / scale if scale > 0.0 else worst
