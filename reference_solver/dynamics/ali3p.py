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

W is a preconditioner only: every residual is evaluated at the current iterate, so W, factored
once per step at the predictor (tangent.py), changes the iteration count, never the answer.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from reference_solver.dynamics.loads import Loads
from reference_solver.dynamics.projection import project
from reference_solver.dynamics.tangent import Tangent
from reference_solver.errors import ConvergenceError
from reference_solver.system import ConstraintSystem

PENALTY = 1e8
"""The penalty of each constraint row relative to the inertia it acts on: alpha_i = PENALTY 4/h^2 /
(C_q M^-1 C_q^T)_ii, so h^2/4 alpha_i C_q M^-1 C_q^T has unit-PENALTY diagonal and the augmented
Lagrangian contracts by 1/(1 + PENALTY s^2) per iteration along a direction whose singular value in
those units is s, whatever the rows' units. Large, since s is small along a long chain (A02's
smallest is 0.014 at 30 degrees from its singular position) and vanishes at a singular one; the
price is lambda* carrying alpha times C's round-off, so the output multipliers are recomputed at
each state (Ali3p.multipliers)."""
NEWTON_STEPS = 40
TOLERANCE = 1e-13
"""Newton stops when the scaled constraint residual is below TOLERANCE and so is the scaled update,
or the update, below STALLED, shrinks by less than SLOW: round-off, or a step ending next to a singular
configuration, where the multipliers converge slowly along the freedoms C_q is about to lose (the
constraints hold them only to second order there)."""
STALLED = 1e-9
SLOW = 0.9
"""An update below STALLED that shrinks by less than this factor has stalled."""
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
        self.tangent = Tangent(system, dense_weight=self.stiff)
        self.weight = np.diag(mass)
        self.alpha = np.zeros(0)
        self.evaluations = 0

    def _factor(self, q: np.ndarray, qd: np.ndarray, t: float, jac: np.ndarray) -> None:
        """Factor W at (q, qd, t); the penalties alpha are fixed at the first factorization."""
        h = self.h
        if self.alpha.size == 0:
            inertia = np.einsum("ij,j,ij->i", jac, 1 / self.mass, jac)
            typical = float(np.max(inertia, initial=0.0)) or 1.0
            self.alpha = PENALTY * 4 / (h * h) / np.maximum(inertia, 1e-12 * typical)
        if not self.stiff:
            self.tangent.factor(self.mass if self.tangent.banded else self.weight, jac, self.alpha, h * h / 4)
            return
        stiffness, damping = self._load_derivatives(q, qd, t)
        self.weight = np.diag(self.mass) + h / 2 * damping + h * h / 4 * stiffness
        self.tangent.factor(self.weight, jac, self.alpha, h * h / 4)

    def _load_derivatives(self, q: np.ndarray, qd: np.ndarray, t: float) -> tuple[np.ndarray, np.ndarray]:
        """K = -dQ_e/dq and D = -dQ_e/dq' by central differences."""
        n = q.size
        stiffness, damping = np.zeros((n, n)), np.zeros((n, n))
        scales = self.system.column_scales
        for k in range(n):
            e = np.zeros(n)
            e[k] = dq = DIFFERENCE * scales[k]
            plus, minus = self.loads(q + e, qd, t).generalized, self.loads(q - e, qd, t).generalized
            stiffness[:, k] = -(plus - minus) / (2 * dq)
            e[k] = dv = DIFFERENCE * max(scales[k], float(np.abs(qd[k])))
            plus, minus = self.loads(q, qd + e, t).generalized, self.loads(q, qd - e, t).generalized
            damping[:, k] = -(plus - minus) / (2 * dv)
        return stiffness, damping

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        return self.tangent.solve(rhs)

    def weigh(self, x: np.ndarray) -> np.ndarray:
        """P x."""
        return self.weight @ x if self.stiff else self.mass * x

    def step(self, s: StepState) -> StepState:
        """The state at s.t + h: Newton with multiplier updates on the trapezoidal equations (W
        factored at the predictor), then the projections of the rates."""
        h, mass, system = self.h, self.mass, self.system
        t = s.t + h
        hat_v = -(2 / h * s.q + s.qd)
        hat_a = -(4 / (h * h) * s.q + 4 / h * s.qd + s.qdd)
        q = s.q + h * s.qd + h * h / 2 * s.qdd
        multipliers = s.multipliers.copy()
        cols, rows = system.column_scales, system.row_scales
        previous, size, violation = np.inf, np.inf, np.inf
        for iterations in range(1, NEWTON_STEPS + 1):
            c, jac, _ = system.evaluate(q, t)
            self.evaluations += 1
            qd, qdd = 2 / h * q + hat_v, 4 / (h * h) * q + hat_a
            if iterations == 1:
                self._factor(q, qd, t, jac)
            else:
                multipliers += self.alpha * c
            load = self.loads(q, qd, t).generalized
            residual = h * h / 4 * (mass * qdd + jac.T @ (self.alpha * c + multipliers) - load)
            update = -self.solve(residual)
            q = q + update
            size = float(np.max(np.abs(update / cols)))
            violation = float(np.max(np.abs(c / rows), initial=0.0))
            if violation <= TOLERANCE and (size <= TOLERANCE or STALLED > size > SLOW * previous):
                break
            previous = size
        else:
            raise ConvergenceError(
                f"{system.scenario.name}: ALI3-P's Newton iteration did not converge at t={t:.6g} "
                f"(update {size:.2g}, constraint residual {violation:.2g})",
                time=t,
                q=q,
            )
        jac = system.jacobian(q, t)
        qd, qdd = 2 / h * q + hat_v, 4 / (h * h) * q + hat_a
        qd, _ = project(self, jac, qd, -system.c_t(t))
        qdd, _ = project(self, jac, qdd, system.q_d(q, qd, t))
        return StepState(t, q, qd, qdd, multipliers, jac, iterations)

    def multipliers(self, s: StepState, load: np.ndarray) -> np.ndarray:
        """The Lagrange multipliers at the state (q, q'): M q'' + C_q^T lambda = Q_e with
        C_q q'' = Q_d, as the partitioned method computes them (lambda* carries the augmented
        Lagrangian's round-off, alpha times that of C). With P = M they are the multipliers of the
        M-orthogonal projection of M^-1 Q_e (so also defined, minimum-norm, at a singular
        configuration); with force elements, least squares on the projected q''."""
        q_d = self.system.q_d(s.q, s.qd, s.t)
        if not self.stiff:
            return project(self, s.jac, load / self.mass, q_d)[1]
        return np.linalg.lstsq(s.jac.T, load - self.mass * s.qdd, rcond=None)[0]
