"""Position, velocity and acceleration analysis over a time grid: the textbook's kinematic loop.

At each time point: Newton-Raphson from the predictor q + h q_dot + h^2/2 q_ddot, then
C_q q_dot = -C_t and C_q q_ddot = Q_d with the same factors. The loop refuses to cross a singular
configuration: it stops with an error when C_q's conditioning collapses, when its determinant changes
sign between two time points (a dead centre or a jump to the other branch lies between), or when
Newton fails next to a singular configuration.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

import reference_solver.compiled as compiled_path
from reference_solver.diagnostics import rank_report
from reference_solver.errors import AssemblyError, ConvergenceError, SingularConfigurationError, SolverError
from reference_solver.factorization import Factorization
from reference_solver.limits import (
    ASSEMBLY_ITERATIONS,
    JUMP_FLOOR,
    JUMP_FRACTION,
    NEAR_SINGULAR,
    SINGULAR_RCOND,
)
from reference_solver.mobility import check_mobility
from reference_solver.newton import NewtonResult, NewtonSettings, newton
from reference_solver.solution import Analysis
from reference_solver.system import ConstraintSystem
from scenarios.limits import MAX_DENSE_ROWS
from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory


def assemble(system: ConstraintSystem, q_guess: np.ndarray, t: float, tolerance: float) -> np.ndarray:
    """A configuration satisfying every constraint at t, by damped Newton from the rough guess."""
    settings = NewtonSettings(tolerance, tolerance, max_iterations=ASSEMBLY_ITERATIONS, damped=True)
    result = newton(system, q_guess, t, settings)
    if result.converged:
        return result.q
    c = system.residual(result.q, t) / system.row_scales
    worst = np.argsort(-np.abs(c))[:4]
    rows = tuple(system.labels[k] for k in worst if abs(c[k]) > 10 * tolerance)
    report = rank_report(system.scaled_jacobian(system.jacobian(result.q, t)), system.labels)
    if rows:
        why = (
            f"after {result.iterations} iterations the constraints {', '.join(rows)} still miss by up to "
            f"{np.max(np.abs(c)):.3g} (relative to the characteristic length "
            f"{system.layout.length_scale:.6g})"
        )
    elif report.deficiency == 0:  # C_q regular, every row within 10 tolerances: a floor of round-off
        largest, length = float(np.max(np.abs(result.q), initial=0.0)), system.layout.length_scale
        why = (
            f"Newton-Raphson stopped with the constraints missing by up to "
            f"{np.max(np.abs(c), initial=0.0):.3g}, above the tolerance {tolerance:.3g}, where C_q is "
            f"regular: the round-off of coordinates as large as {largest:.3g} is about "
            f"{np.finfo(float).eps * largest / length:.3g} (relative to the characteristic length "
            f"{length:.6g})"
        )
    else:
        why = (
            f"the constraints hold (to {np.max(np.abs(c), initial=0.0):.3g}) but C_q is singular there, "
            f"rank deficiency {report.deficiency}, dependent rows: "
            f"{', '.join(report.dependent_rows) or 'unknown'}: "
            "a constraint the others already hold at this configuration (independent elsewhere, so the "
            "mobility check passed it)"
        )
    raise AssemblyError(
        f"{system.scenario.name}: the mechanism cannot assemble at t={t:.6g}: {why}",
        time=t,
        q=result.q,
        rank_deficiency=report.deficiency,
        dependent_rows=report.dependent_rows,
    )


def _singular(system: ConstraintSystem, q: np.ndarray, t: float, why: str) -> SingularConfigurationError:
    """The error for a singular configuration at (or next to) q."""
    report = rank_report(system.scaled_jacobian(system.jacobian(q, t)), system.labels, NEAR_SINGULAR)
    deficiency = max(1, report.deficiency)
    rows = report.dependent_rows
    return SingularConfigurationError(
        f"{system.scenario.name}: singular configuration at t={t:.6g}: {why}; C_q rank deficiency "
        f"{deficiency}, dependent rows: {', '.join(rows) or 'unknown'}",
        time=t,
        q=q.copy(),
        rank_deficiency=deficiency,
        dependent_rows=rows,
    )


def _rates(
    system: ConstraintSystem, factors: Factorization, q: np.ndarray, t: float
) -> tuple[np.ndarray, np.ndarray]:
    """q_dot from C_q q_dot = -C_t and q_ddot from C_q q_ddot = Q_d, with the scaled factors."""
    rows, cols = system.row_scales, system.column_scales
    qd = factors.solve(-system.c_t(t) / rows) * cols
    qdd = factors.solve(system.q_d(q, qd, t) / rows) * cols
    return qd, qdd


def analyse(
    scenario: Scenario,
    times: Sequence[float] | np.ndarray | None = None,
    tolerance: float = 1e-12,
    max_iterations: int = 25,
    compiled: bool | None = True,
) -> Analysis:
    """The full kinematic analysis of `scenario` on `times` (default: the scenario's grid).

    `compiled` runs the compiled path (reference_solver.compiled) when it can; whatever it cannot do, or
    any abnormal event it meets, is handed to this loop, which then runs from the start. `compiled`
    None takes the compiled path where it pays (compiled.pays: its kernels loaded already, or enough
    work) or where the problem is too large for this loop's dense solves.
    """
    grid = np.asarray(scenario.times() if times is None else times, dtype=float)
    coordinates = 3 * len(scenario.bodies)
    if compiled_path.pays("path", coordinates, grid.size, compiled) or (
        compiled is None and coordinates > MAX_DENSE_ROWS
    ):
        done = compiled_path.analyse(scenario, grid, tolerance, max_iterations)
        if done is not None:
            return done
    system = ConstraintSystem(scenario)
    layout = system.layout
    if layout.size > MAX_DENSE_ROWS:  # its SVDs and LU factors are cubic, uninterruptible calls
        raise SolverError(
            f"the compiled path could not do this analysis, and the plain path's dense solves of "
            f"{layout.size} coordinates are above the limit of {MAX_DENSE_ROWS} "
            "(scenarios.limits.MAX_DENSE_ROWS): fewer bodies, or finer steps for the compiled path"
        )
    guess = layout.initial_guess(scenario)
    check_mobility(system, guess)
    settings = NewtonSettings(tolerance, tolerance, max_iterations)
    n, count = layout.size, len(grid)
    q_all, qd_all, qdd_all = np.empty((count, n)), np.empty((count, n)), np.empty((count, n))
    iterations, residual, rcond = np.zeros(count, int), np.zeros(count), np.zeros(count)

    q = assemble(system, guess, float(grid[0]), tolerance)
    qd = qdd = np.zeros(n)
    previous: Factorization | None = None
    for k, t in enumerate(grid):
        t = float(t)
        if k > 0:
            t0 = float(grid[k - 1])
            predictor = _predict(q, qd, qdd, t - t0)
            result = newton(system, predictor, t, settings)
            if not result.converged or jumped(system, qd, qdd, t - t0, predictor, result.q):
                result = _approach(system, q, qd, qdd, t0, t, settings)
            q, factors, iterations[k], residual[k] = (
                result.q,
                result.factors,
                result.iterations,
                result.residual,
            )
        else:
            result = newton(system, q, t, settings)
            q, factors, residual[k] = result.q, result.factors, result.residual
        assert factors is not None
        if factors.rcond < SINGULAR_RCOND:
            raise _singular(system, q, t, f"C_q reciprocal condition number {factors.rcond:.2g}")
        if previous is not None and factors.sign != previous.sign:
            t0 = float(grid[k - 1])
            before, after = previous.relative_determinant(factors)
            crossing = t0 + (t - t0) * before / (before - after)
            nearer = q if factors.rcond < previous.rcond else q_all[k - 1]
            raise _singular(
                system,
                nearer,
                crossing,
                f"det C_q changed sign between t={t0:.6g} and t={t:.6g} (a singular configuration "
                "or a jump to another assembly branch lies between)",
            )
        previous = factors
        qd, qdd = _rates(system, factors, q, t)
        q_all[k], qd_all[k], qdd_all[k], rcond[k] = q, qd, qdd, factors.rcond
    return Analysis(layout, grid, q_all, qd_all, qdd_all, iterations, residual, rcond)


def _predict(q: np.ndarray, qd: np.ndarray, qdd: np.ndarray, h: float) -> np.ndarray:
    return q + h * qd + 0.5 * h * h * qdd  # type: ignore[no-any-return]


def jumped(
    system: ConstraintSystem,
    qd: np.ndarray,
    qdd: np.ndarray,
    h: float,
    predictor: np.ndarray,
    end: np.ndarray,
) -> bool:
    """Whether a step of length h, predicted from rates (qd, qdd), left its branch by converging to
    `end` (see JUMP_FRACTION)."""
    scales = system.column_scales
    correction = float(np.max(np.abs(end - predictor) / scales))
    reach = float(np.max((np.abs(h * qd) + h * h * np.abs(qdd)) / scales))
    return correction > max(JUMP_FRACTION * reach, JUMP_FLOOR)


def _approach(
    system: ConstraintSystem,
    q: np.ndarray,
    qd: np.ndarray,
    qdd: np.ndarray,
    t0: float,
    t1: float,
    settings: NewtonSettings,
) -> NewtonResult:
    """Reach t1 from the solution at t0 in halved steps after Newton failed in one.

    Either a poor predictor was the trouble and t1 is reached, or the steps shrink against a limit
    no configuration of the branch lies beyond (a dead centre, the end of a cam contact branch), or
    every step forward jumps to another solution: then the error names the singular configuration
    met there, at the last time reached. A regular configuration where Newton still fails gives a
    ConvergenceError.
    """
    t, h = t0, (t1 - t0) / 2
    last = None
    while abs(h) > 1e-12 * max(abs(t1), abs(t1 - t0)):
        target = min(t + h, t1) if t1 > t0 else max(t + h, t1)
        predictor = _predict(q, qd, qdd, target - t)
        result = newton(system, predictor, target, settings)
        factors = result.factors
        regular = factors is not None and factors.rcond >= SINGULAR_RCOND
        if result.converged and regular and not jumped(system, qd, qdd, target - t, predictor, result.q):
            assert factors is not None
            q, t, last = result.q, target, result
            qd, qdd = _rates(system, factors, q, t)
            if t == t1:
                return result
            h *= 2
        else:
            h /= 2
    report = rank_report(system.scaled_jacobian(system.jacobian(q, t)), system.labels)
    if report.smallest < NEAR_SINGULAR:
        raise _singular(
            system,
            q,
            t,
            f"no configuration beyond this time on this branch (Newton-Raphson fails or leaves the "
            f"branch at any step forward; smallest singular value ratio {report.smallest:.2g})",
        )
    iterations = last.iterations if last else settings.max_iterations
    raise ConvergenceError(
        f"{system.scenario.name}: Newton-Raphson did not converge at t={t1:.6g} (stuck at t={t:.6g} "
        f"after {iterations} iterations) at a regular configuration",
        time=t,
        q=q.copy(),
    )


def solve(
    scenario: Scenario,
    times: Sequence[float] | np.ndarray | None = None,
    tolerance: float = 1e-12,
    compiled: bool = True,
) -> Trajectory:
    """The reference trajectory of every body of `scenario` (all three levels, plus contact phi)."""
    return analyse(scenario, times, tolerance, compiled=compiled).trajectory()
