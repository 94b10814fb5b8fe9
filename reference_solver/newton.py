"""Newton-Raphson on C(q, t) = 0 at one time point, judged in scaled units."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from reference_solver.factorization import Factorization, factorize
from reference_solver.limits import BACKTRACK_HALVINGS, ROUND_OFF_ULPS
from reference_solver.system import ConstraintSystem


@dataclass(frozen=True)
class NewtonSettings:
    """Converged when max |dq| < step_tolerance and max |C| < residual_tolerance (scaled units),
    within `max_iterations`; `damped` adds a backtracking line search (used for assembly)."""

    step_tolerance: float = 1e-12
    residual_tolerance: float = 1e-12
    max_iterations: int = 25
    damped: bool = False


@dataclass(frozen=True)
class NewtonResult:
    q: np.ndarray
    converged: bool
    iterations: int
    residual: float
    """max |C| in scaled units at q."""
    factors: Factorization | None
    """The scaled Jacobian's factors at q when converged."""


def newton(system: ConstraintSystem, q: np.ndarray, t: float, settings: NewtonSettings) -> NewtonResult:
    """Iterate C_q dq = -C from q. Never raises: the caller diagnoses a failure."""
    q = q.copy()
    rows, cols = system.row_scales, system.column_scales
    step = np.inf
    for iteration in range(settings.max_iterations + 1):
        c, jac, _ = system.evaluate(q, t)
        scaled_c = c / rows
        residual = float(np.max(np.abs(scaled_c))) if c.size else 0.0
        if not np.isfinite(residual):
            return NewtonResult(q, False, iteration, residual, None)
        factors = factorize(system.scaled_jacobian(jac))
        if residual < settings.residual_tolerance and step < _step_tolerance(settings, q / cols):
            return NewtonResult(q, True, iteration, residual, factors)
        if iteration == settings.max_iterations or factors.rcond == 0.0:
            break
        dx = factors.solve(-scaled_c)
        if settings.damped:
            dx = _backtrack(system, q, t, dx, residual)
        q += dx * cols
        step = float(np.max(np.abs(dx))) if dx.size else 0.0
    return NewtonResult(q, False, iteration, residual, None)


def _step_tolerance(settings: NewtonSettings, scaled_q: np.ndarray) -> float:
    """The settings' step tolerance, raised to q's round-off where that is larger (0 stays 0)."""
    tolerance = settings.step_tolerance
    return max(tolerance, _round_off(scaled_q)) if tolerance > 0.0 else tolerance


def _round_off(scaled_q: np.ndarray) -> float:
    """The smallest step Newton can resolve on q (scaled units): ROUND_OFF_ULPS units in the last
    place of its largest coordinate. A step tolerance below it is met only by a step of exactly 0,
    so on large coordinates (a gear after thousands of turns: 1.6e4 rad) every Newton call would
    fail and the time loop crawl in halved steps; below 1e3 scaled it is under 1e-12 and changes
    nothing."""
    return ROUND_OFF_ULPS * float(np.finfo(float).eps) * float(np.max(np.abs(scaled_q), initial=0.0))


def _backtrack(
    system: ConstraintSystem, q: np.ndarray, t: float, dx: np.ndarray, residual: float
) -> np.ndarray:
    """Halve the scaled step until the scaled residual decreases (at most BACKTRACK_HALVINGS times)."""
    scale = 1.0
    for _ in range(BACKTRACK_HALVINGS):
        trial = q + scale * dx * system.column_scales
        value = np.max(np.abs(system.residual(trial, t) / system.row_scales))
        if np.isfinite(value) and value < residual:
            break
        scale *= 0.5
    return scale * dx  # type: ignore[no-any-return]
