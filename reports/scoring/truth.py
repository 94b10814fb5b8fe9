"""The truth each run is measured against, independent of every engine where it can be.

Where the scenario has a closed form (scenarios.closed_form.exact: a kinematic family's own
mechanism, identified by its digest, eccentric disc cams among the cams) the closed form is the
truth, and the native solver is measured against it like any other engine. Elsewhere (spline and
lobed cam profiles, scenario files that are not a family's own mechanism) the truth is the native
solver solved on a grid REFINE times finer at TRUTH_TOLERANCE, sampled on the scenario's grid.
A dynamic scenario (no closed form) takes the native forward dynamics at DYNAMIC_RTOL, tighter
than any setting the native engine is measured at. Each truth carries its name, stored with every
row measured against it. The force level's truth is named too (scoring.forces): Newton-Euler on the
closed form where every element has a free-body model, else the native inverse dynamics added to
a kinematic truth, or the multipliers a dynamic truth carries.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from reports.scoring.forces import (
    CLOSED_FORM_FORCES,
    NATIVE_INVERSE,
    NATIVE_MULTIPLIERS,
    TRUTH_TOLERANCE,
    closed_form_forces,
    force_columns,
    native_forces,
)
from scenarios import Scenario, Trajectory
from scenarios.closed_form import NoClosedForm, exact

CLOSED_FORM = "closed form"
"""The `truth` of a row measured against its scenario's closed form."""
REFINE = 4
ATTEMPTS = 3
"""How often the native solve is cut short at the time the solver stopped before giving up."""
NATIVE_REFINED = f"native, tolerance {TRUTH_TOLERANCE:g}, grid refined {REFINE}x"
DYNAMIC_RTOL = 1e-13
NATIVE_DYNAMIC = f"native dynamics, DOP853 rtol {DYNAMIC_RTOL:g}"


@dataclass(frozen=True)
class NamedTruth:
    """A truth trajectory and the name that says what it is."""

    trajectory: Trajectory
    name: str
    forces: str = ""
    """The force truth the trajectory's force columns are (scoring.forces.FORCE_TRUTHS); '' none."""


def closed_form(scenario: Scenario, times: np.ndarray) -> Trajectory | None:
    """The closed-form trajectory, or None where there is none for this mechanism (a file that
    takes a family's name but is not the family's own mechanism has none: scenarios.closed_form)."""
    try:
        return exact(scenario, times)
    except NoClosedForm:
        return None


def native_refined(scenario: Scenario, times: np.ndarray) -> Trajectory:
    """The native solver on a grid REFINE times finer at TRUTH_TOLERANCE, sampled on `times` (NaN from
    where it finds no configuration)."""
    return partial_truth(scenario, np.asarray(times, dtype=float), REFINE)


def partial_truth(scenario: Scenario, times: np.ndarray, refine: int = 1) -> Trajectory:
    """The native solution on `times` at TRUTH_TOLERANCE, solved on a grid `refine` times finer; NaN from
    where the solver stops (a singular configuration, no configuration beyond). An empty prefix (no
    assembly) raises the solver's error."""
    import reference_solver  # on first use: the native solver is slow to import

    fine = _refined(times, refine)
    end = fine.size
    for _ in range(ATTEMPTS):
        try:
            solved = reference_solver.solve(scenario, fine[:end], tolerance=TRUTH_TOLERANCE)
            break
        except reference_solver.SolverError as error:
            if error.time is None:
                raise
            end = int(np.searchsorted(fine, error.time, side="left"))
            if end == 0:
                raise
    else:
        raise RuntimeError(f"{scenario.name}: the reference solver kept failing before its last stop")
    return _pad(solved, times, refine)


def _refined(times: np.ndarray, refine: int) -> np.ndarray:
    if refine <= 1 or times.size < 2:
        return times
    steps = np.linspace(0.0, 1.0, refine + 1)[:-1]
    inner = (times[:-1, None] + np.diff(times)[:, None] * steps[None, :]).ravel()
    return np.append(inner, times[-1])


def _pad(solved: Trajectory, times: np.ndarray, refine: int) -> Trajectory:
    """Every `refine`-th point of `solved`, NaN for the grid times it did not reach."""
    count = times.size

    def sample(values: np.ndarray) -> np.ndarray:
        picked = values[::refine]
        out = np.full((count, *values.shape[1:]), np.nan)
        out[: len(picked)] = picked
        return out

    levels = {lv: None if (v := solved.level(lv)) is None else sample(v) for lv in solved.levels}
    extras = {name: sample(values) for name, values in solved.extras.items()}
    return Trajectory(times.copy(), solved.bodies, extras=extras, **levels)  # type: ignore[arg-type]


def independent_truth(scenario: Scenario, times: np.ndarray) -> NamedTruth:
    """The runner's default truth: the closed form where there is one, the refined native solve
    otherwise."""
    grid = np.asarray(times, dtype=float)
    if scenario.analysis == "dynamic":
        from reference_solver.dynamics import simulate  # on first use, as above

        dynamic = simulate(scenario, grid, DYNAMIC_RTOL).trajectory()
        return NamedTruth(dynamic, NATIVE_DYNAMIC, NATIVE_MULTIPLIERS if force_columns(dynamic) else "")
    exact_motion = closed_form(scenario, grid)
    if exact_motion is not None:
        forces = closed_form_forces(scenario, exact_motion)
        if forces is not None:
            extras = {**exact_motion.extras, **forces}
            forced = dataclasses.replace(exact_motion, extras=extras)
            return NamedTruth(forced, CLOSED_FORM, CLOSED_FORM_FORCES)
        return _native_forced(with_native_forces(scenario, grid, exact_motion), CLOSED_FORM)
    return _native_forced(with_native_forces(scenario, grid, native_refined(scenario, grid)), NATIVE_REFINED)


def _native_forced(truth: Trajectory, name: str) -> NamedTruth:
    """A kinematic truth named, with NATIVE_INVERSE as its force truth where it carries forces."""
    return NamedTruth(truth, name, NATIVE_INVERSE if force_columns(truth) else "")


def with_native_forces(scenario: Scenario, times: np.ndarray, truth: Trajectory) -> Trajectory:
    """The truth with the native inverse dynamics' driving forces and reactions added as extras
    (scoring.forces), the force level's truth; unchanged where the native solver cannot give them
    (a body without mass, no configuration on the grid). A truth with no configuration from some
    time on (NaN positions: past a dead point) is returned as it is, without asking the native
    solver, whose approach to that point would cost about half a second only to fail there too."""
    from reference_solver.errors import SolverError  # on first use, as above

    if truth.position is not None and not np.all(np.isfinite(truth.position)):
        return truth  # no configuration somewhere on the grid: nor will the native solver find one
    try:
        forces = native_forces(scenario, times)
    except SolverError:
        return truth
    return dataclasses.replace(truth, extras={**truth.extras, **forces})


def named(value: Trajectory | NamedTruth, fallback: str) -> NamedTruth:
    """A truth hook's answer as a NamedTruth (a hook that returns a bare trajectory gets `fallback`)."""
    return value if isinstance(value, NamedTruth) else NamedTruth(value, fallback)
