"""The force level: a run's driving forces and joint reactions against the force truth.

A run may carry its drivers' forces (`<driver>.force`; `<driver>.x.force`, `<driver>.y.force` for a
point's two rows) and its joints' reactions (`<joint>.fx`, `<joint>.fy`: the force the joint
applies to its first moving body, world axes). They are set against the force truth, which each row
names (FORCE_TRUTHS): where the scenario has a closed form and every element a free-body model,
Newton-Euler body by body on the closed-form motion (scenarios.newton_euler), independent of every
engine, the native solver included; elsewhere the native solver's own: in a driven scenario its
inverse dynamics on its kinematic analysis at TRUTH_TOLERANCE, in free dynamics the multipliers of
its dynamic truth. A native run is judged only against a truth that is not its own.
FORCE_DEFINITION says how the error is made one number.
"""

from __future__ import annotations

import math

import numpy as np

from scenarios.drivers import AbsoluteDriver, RelativeRotationDriver
from scenarios.newton_euler import NoForceTruth, body_forces
from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory

TRUTH_TOLERANCE = 1e-12
"""Newton's tolerance for every native truth: the kinematic one (scoring.truth, stress.truth) and the
force level's inverse dynamics on the native analysis. Defined here, the lowest module that needs it."""
CLOSED_FORM_FORCES = "Newton-Euler body by body on the closed form"
NATIVE_INVERSE = f"native inverse dynamics, tolerance {TRUTH_TOLERANCE:g}"
NATIVE_MULTIPLIERS = "native dynamics' multipliers"
FORCE_TRUTHS = (CLOSED_FORM_FORCES, NATIVE_INVERSE, NATIVE_MULTIPLIERS)
"""What a row's `force_truth` may say; only the first is independent of the native solver."""
DRIVER_SUFFIX = ".force"
REACTION_SUFFIXES = (".fx", ".fy")
FORCE_DEFINITION = (
    "force error = the largest |F - F_native| over the drivers' forces and the joints' reactions on "
    "the grid, over the mechanism's force scale S: the largest native reaction or driving force, a "
    "torque counted as torque / L (L the characteristic length); a torque's error is divided by S L. "
    "Absolute (N, N m) where the native forces are all zero"
)


def force_columns(result: Trajectory) -> list[str]:
    """The driver-force and reaction columns the run carries."""
    return [c for c in result.extras if c.endswith((DRIVER_SUFFIX, *REACTION_SUFFIXES))]


def judges_native(force_truth: str) -> bool:
    """Whether a force truth is independent of the native solver, so that a native run's forces can
    be judged against it."""
    return force_truth == CLOSED_FORM_FORCES


def closed_form_forces(scenario: Scenario, motion: Trajectory) -> dict[str, np.ndarray] | None:
    """The Newton-Euler forces on a closed-form motion; None where an element has no free-body model
    (gears, cams) or the motion has no configuration somewhere (NaN)."""
    try:
        found = body_forces(scenario, motion)
    except NoForceTruth:
        return None
    return found if all(np.all(np.isfinite(v)) for v in found.values()) else None


def native_forces(scenario: Scenario, times: np.ndarray) -> dict[str, np.ndarray]:
    """Every driver's force and joint's reaction from the native inverse dynamics on `times`."""
    from reference_solver import analyse  # on first use: the native solver is slow to import
    from reference_solver.dynamics import inverse_dynamics

    found = inverse_dynamics(scenario, analyse(scenario, times, tolerance=TRUTH_TOLERANCE))
    return {k: v for k, v in found.items() if k.endswith((DRIVER_SUFFIX, *REACTION_SUFFIXES))}


def force_errors(scenario: Scenario, result: Trajectory, native: dict[str, np.ndarray]) -> dict[str, float]:
    """{driver_force_error, reaction_error, error_force} by FORCE_DEFINITION (NaN for a kind the
    run does not carry); KeyError naming a column the native solver does not have."""
    columns = force_columns(result)
    unknown = [c for c in columns if c not in native]
    if unknown:
        raise KeyError(f"the native solver gives no {', '.join(unknown)} (known: {', '.join(native)})")
    length = scenario.characteristic_length
    torques = _torque_columns(scenario)
    scale = max(
        (float(np.max(np.abs(v))) / (length if k in torques else 1.0) for k, v in native.items()),
        default=0.0,
    )

    def worst(kind: tuple[str, ...]) -> float:
        picked = [c for c in columns if c.endswith(kind)]
        if not picked:
            return math.nan
        errors = []
        for c in picked:
            unit = (scale * length if c in torques else scale) or 1.0
            errors.append(float(np.max(np.abs(result.extras[c] - native[c]))) / unit)
        return max(errors)

    drivers, reactions = worst((DRIVER_SUFFIX,)), worst(REACTION_SUFFIXES)
    both = [e for e in (drivers, reactions) if not math.isnan(e)]
    return {
        "driver_force_error": drivers,
        "reaction_error": reactions,
        "error_force": max(both) if both else math.nan,
    }


def _torque_columns(scenario: Scenario) -> set[str]:
    """The driver-force columns that are torques (a driven angle)."""
    found = set()
    for driver in scenario.drivers:
        angle = isinstance(driver, RelativeRotationDriver) or (
            isinstance(driver, AbsoluteDriver) and driver.coordinate == "theta"
        )
        if angle:
            found.add(f"{driver.name}{DRIVER_SUFFIX}")
    return found
