"""Running an Exudyn model from its assembled start (adapters.exudyn.assembly), three ways:
generalized-alpha (index 3, after a run-in on kinematic scenes: adapters.exudyn.run_in), the
trapezoidal rule with index-2 constraints, and a static solve per time point. The march steps onto
the output times (adapters.lattice.outputs_on_steps); only an uneven grid is interpolated, with a
warning saying so.

Everything stays in memory and silent: no solution, sensor or solver files, no console output.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, replace
from typing import Any

import exudyn as exu
import numpy as np

from adapters.base import EngineFailure
from adapters.exudyn.assembly import (
    INITIAL,
    ConstraintProbe,
    States,
    assemble,
    coordinate_scales,
    guarded,
    write_initial,
)
from adapters.exudyn.force_sensors import force_columns
from adapters.exudyn.model import ExudynModel
from adapters.exudyn.run_in import NO_RUN_IN, negative_times, run_in_start
from adapters.lattice import (
    check_grid,
    hermite,
    interpolation_cost,
    lattice_point,
    lattice_steps,
    outputs_on_steps,
)
from scenarios.bodies import GROUND
from scenarios.trajectory import Trajectory

DYNAMIC = {
    "GA": exu.DynamicSolverType.GeneralizedAlpha,
    "TR2": exu.DynamicSolverType.TrapezoidalIndex2,
    "RK44": exu.DynamicSolverType.RK44,
}


@dataclass(frozen=True)
class Plan:
    """How to march: `solver` GA, TR2 or STATIC; the requested step `dt`; GA's spectral radius;
    Newton's tolerance on the increment of each step (or of each static solve); whether the
    integrator keeps Exudyn's modified Newton (else full Newton); the steps of run-in before the
    first output (adapters.exudyn.run_in); `untuned`: Exudyn's own default settings, its own
    initial accelerations, no run-in."""

    solver: str
    dt: float
    rho: float
    tolerance: float
    modified_newton: bool = False
    run_in: int = 0
    untuned: bool = False


@contextmanager
def quiet() -> Iterator[None]:
    """Exudyn's console output off for the duration (it is a process-wide switch)."""
    before = exu.config.printToConsole
    exu.config.printToConsole = False
    try:
        yield
    finally:
        exu.config.printToConsole = before


def simulation_settings(tolerance: float) -> Any:
    """Settings that write no file and print nothing, with full Newton at `tolerance`."""
    s = exu.SimulationSettings()
    s.solution.file.write = False
    s.solution.sensors.active = False
    s.solution.restart.write = False
    s.show.computationTime = s.show.statistics = s.show.globalTimers = False
    for solver in (s.staticSolver, s.timeIntegration):
        solver.verboseMode = 0
        solver.verboseModeFile = 0
        solver.stepInformation = 0
        solver.adaptiveStep = False
        solver.newton.useModifiedNewton = False
        solver.newton.adaptInitialResidual = False  # else a blown-up first iterate passes as converged
        # converge on the Newton increment, not on the residual: the residual mixes forces with
        # constraint gaps, so a tolerance on it depends on the masses
        solver.newton.residualMode = 1
        solver.newton.relativeTolerance = tolerance
        solver.newton.absoluteTolerance = tolerance
    s.timeIntegration.automaticStepSize = False
    return s


def untuned_settings() -> Any:
    """Exudyn's own default settings, quiet and file-free only (what a new user's model runs with)."""
    s = exu.SimulationSettings()
    s.solution.file.write = False
    s.solution.sensors.active = False
    s.solution.restart.write = False
    s.show.computationTime = s.show.statistics = s.show.globalTimers = False
    s.timeIntegration.verboseMode = 0
    s.timeIntegration.stepInformation = 0
    s.staticSolver.verboseMode = 0
    return s


def march(
    model: ExudynModel, plan: Plan, times: np.ndarray, settings: Any, start: States | None = None
) -> tuple[States, int]:
    """The states on `times` and the number of engine steps taken, from `start` (found by
    `assemble` before), or from a start assembled here."""
    if start is None:
        start = assemble(model, float(times[0]), settings)
    else:
        write_initial(model, start)
    if len(times) == 1:
        return start, 0
    if plan.solver == "STATIC":
        if model.force_sensors:
            warnings.warn(STATIC_FORCES_REASON, stacklevel=2)
        return _static_load_steps(model, times, settings, plan.tolerance), len(times) - 1
    return _integrate(model, plan, times, settings, start)


def _recorder(model: ExudynModel, times: np.ndarray, states: States, tolerance: float) -> Callable[..., bool]:
    interval = float(times[1] - times[0])
    data = model.mbs.systemData

    def record(mbs: Any, t: float) -> bool:
        k = round((t - times[0]) / interval)
        if 0 < k < len(times) and abs(t - times[k]) <= tolerance:
            states.q[k] = data.GetODE2Coordinates()
            states.v[k] = data.GetODE2Coordinates_t()
            states.a[k] = data.GetODE2Coordinates_tt()
        return True

    return record


def _empty(n_times: int, n: int) -> States:
    q, v, a = (np.full((n_times, n), np.nan) for _ in range(3))
    return States(q, v, a)


def _integrate(
    model: ExudynModel, plan: Plan, times: np.ndarray, settings: Any, start: States
) -> tuple[States, int]:
    """March whole steps from `plan.run_in` steps before the first output time past the last, the
    step being `plan.dt` or the largest below it that puts the outputs on the steps (adapters.lattice),
    Exudyn's sensors recording every step; an output between two steps (an uneven grid) is the Hermite
    interpolant of the two, with a warning (Exudyn's solver runs in one call: no side step)."""
    check_grid(times, float(times[0]))
    t0, h, n = float(times[0]), outputs_on_steps(times, plan.dt), plan.run_in
    begin = run_in_start(model, settings, t0, h, n) if n else None
    if isinstance(begin, str):
        warnings.warn(NO_RUN_IN.format(reason=begin), stacklevel=2)
        begin, n = None, 0
    first = t0 - n * h
    steps = lattice_steps(t0, float(times[-1]), h) + n
    ti = settings.timeIntegration
    ti.generalizedAlpha.spectralRadius = plan.rho
    settings.solution.sensors.active = True
    settings.solution.sensors.writePeriod = 0.5 * h  # every step, once
    solver = DYNAMIC[plan.solver]
    initial = _initial_forces(model, settings, solver, t0, h) if n == 0 and not plan.untuned else None
    if begin is not None:
        write_initial(model, begin)
    # the assembled start has its accelerations; an untuned run lets Exudyn compute them
    ti.generalizedAlpha.computeInitialAccelerations = plan.untuned
    with negative_times():
        ti.startTime, ti.endTime, ti.numberOfSteps = first, first + steps * h, steps
        guarded(model, "dynamicSolver", lambda: model.mbs.SolveDynamic(settings, solverType=solver))
    lattice = _sensed(model, first, h, steps)
    lattice = States(lattice.q[n:], lattice.v[n:], lattice.a[n:])
    scale = coordinate_scales(model)[0]
    if n and float(np.max(np.abs(lattice.q[0] - start.q[0]) / scale)) > SAME_START:
        # the run-in passed a singular configuration onto another branch: start without it
        model.run_in_starts[(t0, h, n)] = OTHER_BRANCH
        warnings.warn(NO_RUN_IN.format(reason=OTHER_BRANCH), stacklevel=2)
        write_initial(model, start)
        return _integrate(model, replace(plan, run_in=0), times, settings, start)
    states = _on_grid(lattice, times, h, scale)
    angle = {body: states.q[:, k + 2] for body, k in model.index.items()}
    states.forces = force_columns(model.mbs, model.force_sensors, times, h, initial, angle)
    return states, steps


SAME_START = 1e-8
"""The run-in reaches the assembled start when its positions there agree to this (over the
coordinates' scales; both are on the constraints to Newton's tolerance)."""
OTHER_BRANCH = "it reaches the start on another assembly branch"


def _initial_forces(model: ExudynModel, settings: Any, solver: Any, t0: float, h: float) -> list[np.ndarray]:
    """Each force sensor's value at t0: Exudyn records a start it did not solve as zero, so one step
    is taken first with Exudyn's own initial-acceleration solve, whose multipliers are the start's
    forces; the start is then restored (the run itself keeps the assembled accelerations)."""
    if not model.force_sensors:
        return []
    data = model.mbs.systemData
    kept = [
        np.array(get(INITIAL))
        for get in (data.GetODE2Coordinates, data.GetODE2Coordinates_t, data.GetODE2Coordinates_tt)
    ]
    ti = settings.timeIntegration
    ti.startTime, ti.endTime, ti.numberOfSteps = t0, t0 + h, 1
    ti.generalizedAlpha.computeInitialAccelerations = True
    guarded(model, "dynamicSolver", lambda: model.mbs.SolveDynamic(settings, solverType=solver))
    found = [np.asarray(model.mbs.GetSensorStoredData(s.handle))[0, 1:].copy() for s in model.force_sensors]
    write_initial(model, States(kept[0][None, :], kept[1][None, :], kept[2][None, :]))
    return found


def _sensed(model: ExudynModel, t0: float, h: float, steps: int) -> States:
    """The states the sensors stored at each lattice point t0 + k h, k = 0..steps; an
    EngineFailure when one is missing."""
    states = _empty(steps + 1, len(model.guess))
    for index, width, handles in model.sensors:
        for level, handle in zip((states.q, states.v, states.a), handles, strict=True):
            data = np.asarray(model.mbs.GetSensorStoredData(handle))
            k = np.rint((data[:, 0] - t0) / h).astype(int)
            keep = (k >= 0) & (k <= steps) & (np.abs(data[:, 0] - t0 - k * h) <= 1e-6 * h)
            level[k[keep], index : index + width] = data[keep, 1:]
    _check_complete(states, t0 + h * np.arange(steps + 1))
    return states


INTERPOLATED = (
    "Exudyn: {count} of {total} output times fall between its steps (an uneven grid) and are "
    "interpolated: cubic Hermite in position and velocity, linear in acceleration; the positions' "
    "interpolation error is about {cost:.2g} (lengths over the characteristic length, angles in rad: "
    "their largest difference from the quintic through the accelerations too)"
)


def _on_grid(lattice: States, times: np.ndarray, h: float, scale: np.ndarray) -> States:
    """The lattice states at the output times (adapters.lattice); a warning where any is interpolated,
    with an estimate of what that costs in positions (each coordinate over its `scale`)."""
    out = _empty(len(times), lattice.q.shape[1])
    between, cost = 0, 0.0
    for i, t in enumerate(times):
        whole, rest = lattice_point(float(times[0]), float(t), h)
        if rest == 0.0:
            out.q[i], out.v[i], out.a[i] = lattice.q[whole], lattice.v[whole], lattice.a[whole]
            continue
        between += 1
        ends = [(level.q[j], level.v[j], level.a[j]) for level in (lattice,) for j in (whole, whole + 1)]
        out.q[i], out.v[i], out.a[i] = hermite(rest / h, h, ends[0], ends[1])
        cost = max(cost, float(np.max(interpolation_cost(rest / h, h, ends[0], ends[1]) / scale)))
    if between:
        warnings.warn(INTERPOLATED.format(count=between, total=len(times), cost=cost), stacklevel=2)
    return out


STATIC_FORCES_REASON = (
    "forces not given: the static solve per output time has no inertia, so its multipliers are not "
    "the driving forces and reactions of the moving mechanism"
)


def _static_load_steps(model: ExudynModel, times: np.ndarray, settings: Any, tolerance: float) -> States:
    """The static solve at each grid time, as Exudyn's load steps (one per grid interval)."""
    static = settings.staticSolver
    static.newton.relativeTolerance, static.newton.absoluteTolerance = tolerance, tolerance
    static.numberOfLoadSteps = len(times) - 1
    static.loadStepStart, static.loadStepDuration = float(times[0]), float(times[-1] - times[0])
    states = _empty(len(times), len(model.guess))
    states.q[0] = np.array(model.mbs.systemData.GetODE2Coordinates(INITIAL))
    interval = float(times[1] - times[0])
    model.mbs.SetPostStepUserFunction(_recorder(model, times, states, 1e-6 * interval))
    guarded(model, "staticSolver", lambda: model.mbs.SolveStatic(settings))
    _check_complete(states, times)
    probe = ConstraintProbe(model, settings)
    scales = coordinate_scales(model)
    for k, t in enumerate(times):
        states.v[k], states.a[k] = probe.rates(states.q[k], float(t), *scales)
    probe.close(settings)
    return states


def _check_complete(states: States, times: np.ndarray) -> None:
    missing = np.flatnonzero(~np.isfinite(states.q).all(axis=1))
    if missing.size:
        raise EngineFailure(f"Exudyn reported no state at t = {times[missing[0]]}", float(times[missing[0]]))


def trajectory(model: ExudynModel, times: np.ndarray, states: States) -> Trajectory:
    """The canonical trajectory of the output bodies, with each cam's `<contact>.phi` and the
    scenario's angle outputs (relative angles of bodies)."""
    bodies = model.scenario.output_bodies
    cols = [np.arange(model.index[b], model.index[b] + 3) for b in bodies]
    pick = [np.stack([level[:, c] for c in cols], axis=1) for level in (states.q, states.v, states.a)]
    extras = {name: states.q[:, i].copy() for name, i in model.phi_index.items()}
    extras.update(states.forces)
    for name, (cam, follower, phi_of, guess) in model.phi_from_poses.items():
        extras[f"{name}.phi"] = _phi_series(model, states.q, cam, follower, phi_of, guess)

    def angle(body: str) -> np.ndarray:
        return np.zeros(len(states.q)) if body == GROUND else states.q[:, model.index[body] + 2]

    for output in model.scenario.angle_outputs:
        extras[output.name] = angle(output.body) - angle(output.relative_to)
    grid = np.asarray(times, dtype=float)
    return Trajectory(grid, bodies, position=pick[0], velocity=pick[1], acceleration=pick[2], extras=extras)


def _phi_series(
    model: ExudynModel, q: np.ndarray, cam: str, follower: str, phi_of: Any, guess: float
) -> np.ndarray:
    def pose(body: str, row: np.ndarray) -> np.ndarray:
        return np.zeros(3) if body == GROUND else row[model.index[body] : model.index[body] + 3]

    raw = np.unwrap([phi_of(pose(cam, row), pose(follower, row)) for row in q])
    turns = round((guess - raw[0]) / (2.0 * math.pi))
    return np.asarray(raw + 2.0 * math.pi * turns)
