"""Forward dynamics by the index-3 augmented Lagrangian formulation with projections (ALI3-P;
Bayo, Garcia de Jalon and Serna 1988; Cuadrado, Cardenal, Morer and Bayo 2000), the method the
IFToMM benchmark's authors use through singular configurations.

    M q'' + C_q^T (alpha C + lambda*) = Q_e,       lambda* <- lambda* + alpha C  (each iteration)

discretized by the trapezoidal rule (q'_{n+1} = 2/h q_{n+1} + qhat'_n, q''_{n+1} = 4/h^2 q_{n+1} +
qhat''_n) and solved for q_{n+1} by Newton, the equation scaled by h^2/4, with the tangent
W = P + h^2/4 alpha C_q^T C_q, P = M + h/2 D + h^2/4 K (D = -dQ_e/dq', K = -dQ_e/dq). W is
positive definite whatever the rank of C_q: the method needs no independent coordinates and
passes configurations where C_q loses rank. The converged q'' and q' are then projected
(P-orthogonally) onto C_q q' + C_t = 0 and C_q q'' = Q_d (projection.py).

W is a preconditioner only: every residual is evaluated at the current iterate, so a factorization
kept over many steps (refreshed when Newton slows) changes the iteration count, never the answer.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.linalg import lu_factor, lu_solve

from reference_solver.dynamics.loads import Loads
from reference_solver.dynamics.partition import State, driver_power
from reference_solver.dynamics.projection import project
from reference_solver.errors import ConvergenceError
from reference_solver.system import ConstraintSystem

PENALTY = 1e3
"""The largest ratio, over the coordinates, of the penalty's share of W's diagonal to the mass's,
h^2/4 alpha (C_q^T C_q)_kk / M_kk. Larger speeds the multipliers' convergence but amplifies the
round-off of C (alpha C enters the residual) into the lightest coordinates by about as much."""
NEWTON_STEPS = 40
TOLERANCE = 1e-13
"""Newton stops when the scaled update and the scaled constraint residual are below TOLERANCE, or
when below STALLED an update no longer halves (round-off reached)."""
STALLED = 1e-11
SLOW = 6
"""Newton iterations beyond which W is refactored at the next step."""
DIFFERENCE = 1e-7
"""Relative step of the finite differences giving K and D (only scenarios with force elements)."""


@dataclass(frozen=True)
class StepState:
    """The trapezoidal rule's state at one time: positions, projected rates, the augmented
    Lagrangian's multipliers lambda*, the constraint Jacobian there and the iteration count."""

    t: float
    q: np.ndarray
    qd: np.ndarray
    qdd: np.ndarray
    multipliers: np.ndarray
    jac: np.ndarray
    iterations: int = 0


class Ali3p:
    """The ALI3-P time step of one scenario at a fixed step h."""

    def __init__(self, system: ConstraintSystem, mass: np.ndarray, loads: Loads, h: float) -> None:
        self.system, self.mass, self.loads, self.h = system, mass, loads, h
        self.stiff = bool(system.scenario.forces)
        self.factors: tuple[np.ndarray, np.ndarray] | None = None
        self.weight = np.diag(mass)
        self.alpha = 0.0
        self.evaluations = 0
        self.refactor = True

    def _tangent(self, q: np.ndarray, qd: np.ndarray, t: float, jac: np.ndarray) -> None:
        """Factor W at (q, qd, t); alpha is fixed at the first factorization."""
        h = self.h
        if self.alpha == 0.0:
            columns = np.einsum("ij,ij->j", jac, jac)
            used = columns > 0
            ratio = float(np.min(self.mass[used] / columns[used])) if np.any(used) else 1.0
            self.alpha = PENALTY * ratio / (h * h / 4)
        weight = np.diag(self.mass)
        if self.stiff:
            stiffness, damping = self._load_derivatives(q, qd, t)
            weight = weight + h / 2 * damping + h * h / 4 * stiffness
        self.weight = weight
        tangent = weight + h * h / 4 * self.alpha * (jac.T @ jac)
        self.factors = lu_factor(tangent, check_finite=False)
        self.refactor = False

    def _load_derivatives(self, q: np.ndarray, qd: np.ndarray, t: float) -> tuple[np.ndarray, np.ndarray]:
        """K = -dQ_e/dq and D = -dQ_e/dq' by central differences."""
        n = q.size
        stiffness, damping = np.zeros((n, n)), np.zeros((n, n))
        scales = self.system.column_scales
        for k in range(n):
            dq = DIFFERENCE * scales[k]
            e = np.zeros(n)
            e[k] = dq
            stiffness[:, k] = -(self.loads(q + e, qd, t).generalized - self.loads(q - e, qd, t).generalized) / (2 * dq)
            dv = DIFFERENCE * max(scales[k], float(np.abs(qd[k])))
            e[k] = dv
            damping[:, k] = -(self.loads(q, qd + e, t).generalized - self.loads(q, qd - e, t).generalized) / (2 * dv)
        return stiffness, damping

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        assert self.factors is not None
        return lu_solve(self.factors, rhs, check_finite=False)

    def step(self, s: StepState) -> StepState:
        """The state at s.t + h: Newton with multiplier updates on the trapezoidal equations, then
        the projections of the rates."""
        h, mass, system = self.h, self.mass, self.system
        t = s.t + h
        if self.refactor or self.factors is None:
            self._tangent(s.q, s.qd, s.t, s.jac)
        hat_v = -(2 / h * s.q + s.qd)
        hat_a = -(4 / (h * h) * s.q + 4 / h * s.qd + s.qdd)
        q = s.q + h * s.qd + h * h / 2 * s.qdd
        multipliers = s.multipliers.copy()
        cols, rows = system.column_scales, system.row_scales
        previous, iterations = np.inf, 0
        for iterations in range(1, NEWTON_STEPS + 1):  # noqa: B007 - the count is reported
            c, jac, _ = system.evaluate(q, t)
            self.evaluations += 1
            if iterations > 1:
                multipliers += self.alpha * c
            qd, qdd = 2 / h * q + hat_v, 4 / (h * h) * q + hat_a
            load = self.loads(q, qd, t).generalized
            residual = h * h / 4 * (mass * qdd + jac.T @ (self.alpha * c + multipliers) - load)
            update = -self.solve(residual)
            q = q + update
            size = float(np.max(np.abs(update / cols)))
            violation = float(np.max(np.abs(c / rows), initial=0.0))
            if (size <= TOLERANCE and violation <= TOLERANCE) or (size < STALLED and size > 0.5 * previous):
                break
            previous = size
            if iterations == 2 * SLOW:  # far slower than W promises: refactor here and go on
                self._tangent(q, qd, t, jac)
        else:
            raise ConvergenceError(
                f"{system.scenario.name}: ALI3-P's Newton iteration did not converge at t={t:.6g} "
                f"(update {size:.2g}, constraint residual {violation:.2g})",
                time=t,
                q=q,
            )
        if iterations > SLOW:
            self.refactor = True
        jac = system.jacobian(q, t)
        qd, qdd = 2 / h * q + hat_v, 4 / (h * h) * q + hat_a
        qd = project(self, jac, qd, -system.c_t(t))
        qdd = project(self, jac, qdd, system.q_d(q, qd, t))
        return StepState(t, q, qd, qdd, multipliers, jac, iterations)


def integrate(
    system: ConstraintSystem, mass: np.ndarray, loads: Loads, start: State, grid: np.ndarray, step: float
) -> tuple[list[State], np.ndarray, int]:
    """ALI3-P from `start` over `grid`, each output interval cut into equal steps of at most `step`:
    the states at the grid's times (multipliers by least squares from the projected q'', so they
    are defined at a singular configuration too: the minimum-norm ones there), the work integrals
    (trapezoidal quadrature of the powers) and the number of constraint evaluations."""
    states, works = [start], [np.zeros(3)]
    current = StepState(start.t, start.q, start.qd, start.qdd, start.lam.copy(), start.jac)
    power = _powers(system, start)
    work = np.zeros(3)
    stepper: Ali3p | None = None
    for end in grid[1:]:
        span = float(end) - current.t
        count = max(1, int(np.ceil(span / step * (1 - 1e-12))))
        h = span / count
        if stepper is None or not np.isclose(stepper.h, h, rtol=1e-9, atol=0.0):
            evaluations = stepper.evaluations if stepper is not None else 0
            stepper = Ali3p(system, mass, loads, h)
            stepper.evaluations = evaluations
        for _ in range(count):
            current = stepper.step(current)
            state = _state(system, mass, loads, current)
            now = _powers(system, state)
            work = work + h / 2 * (power + now)
            power = now
        states.append(_state(system, mass, loads, current, output=True))
        works.append(work.copy())
    return states, np.array(works), stepper.evaluations if stepper is not None else 0


def _state(system: ConstraintSystem, mass: np.ndarray, loads: Loads, s: StepState, output: bool = False) -> State:
    """The kinematic State of a step; at an output point with least-squares multipliers."""
    load = loads(s.q, s.qd, s.t)
    lam = s.multipliers
    if output:
        lam = np.linalg.lstsq(s.jac.T, load.generalized - mass * s.qdd, rcond=None)[0]
    return State(s.t, s.q, s.qd, s.qdd, lam, s.jac, load)


def _powers(system: ConstraintSystem, s: State) -> np.ndarray:
    return np.array([s.loads.applied_power, s.loads.dissipation, driver_power(system, s)])
