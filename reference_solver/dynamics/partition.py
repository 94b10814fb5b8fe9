"""Coordinate partitioning: the state of the ODE is the independent coordinates and their rates;
the dependent ones follow from C(q, t) = 0 by Newton and C_q q' = -C_t at every evaluation.

The independent coordinates are the columns a pivoted QR of the scaled C_q leaves over (the best
conditioned dependent block). The partition holds while that block stays well conditioned; the
integrator restarts with a fresh partition when its reciprocal condition number falls below a
fraction of what it was when chosen.

Newton on the dependent coordinates starts from the anchor: the configuration of the integrator's
last accepted step (`anchor`), not the last evaluation. A rejected trial stage can lie far off the
motion (slider_crank_spring/undamped at rtol 1e-6: the crank's rate 1764 rad/s in one stage against
92 in the step before), where Newton may land on the mechanism's other assembly; started from the
last evaluation, every later stage followed it there, and the energy balance ended at 246 against a
kinetic energy of 353.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.linalg import lu_factor, lu_solve, qr

from reference_solver.dynamics.augmented import accelerations
from reference_solver.dynamics.loads import Loads, LoadState
from reference_solver.errors import ConvergenceError
from reference_solver.system import ConstraintSystem

NEWTON_STEPS = 12
RESIDUAL = 1e-14
STALLED = 1e-12
"""Newton stops when every constraint holds to RESIDUAL, relative to the characteristic length, or
when below STALLED an iteration no longer halves it (round-off of the constraint evaluation)."""


@dataclass(frozen=True)
class State:
    """Everything known at one time point."""

    t: float
    q: np.ndarray
    qd: np.ndarray
    qdd: np.ndarray
    lam: np.ndarray
    jac: np.ndarray
    loads: LoadState


def choose_independent(system: ConstraintSystem, jac: np.ndarray) -> np.ndarray:
    """Columns left out of the best conditioned square block of the scaled C_q (pivoted QR)."""
    scaled = system.scaled_jacobian(jac)
    _, _, pivots = qr(scaled, pivoting=True, mode="economic")
    return np.sort(pivots[system.size :])


class Partitioned:
    """The ODE y' = f(t, y), y = (q_I, q_I', work integrals), for one partition."""

    def __init__(
        self, system: ConstraintSystem, mass: np.ndarray, loads: Loads, q: np.ndarray, independent: np.ndarray
    ):
        self.system, self.mass, self.loads = system, mass, loads
        self.independent = independent
        self.dependent = np.setdiff1d(np.arange(system.unknowns), independent)
        self.jac = np.zeros((system.size, system.unknowns))
        self.c_t = np.zeros(system.size)
        Partitioned.restart(self, q)  # this class's start (a subclass's restart may need its own init)
        self.evaluations = 0

    def restart(self, q: np.ndarray) -> None:
        """Newton's next start: q, without a tangent predictor."""
        self.q, self.t, self.factors = q.copy(), np.nan, None
        self.start: tuple[np.ndarray, np.ndarray, tuple[np.ndarray, np.ndarray] | None, np.ndarray] = (
            self.q,
            self.jac,
            None,
            self.c_t,
        )

    def anchor(self, t: float, y: np.ndarray) -> None:
        """The configuration at (t, y), the integrator's accepted step, becomes Newton's start."""
        if not (self.t == t and np.array_equal(self.q[self.independent], y[: self.size])):
            self.positions(t, y[: self.size])
        self.start = (self.q, self.jac, self.factors, self.c_t)

    @property
    def size(self) -> int:
        return self.independent.size

    def pack(self, state: State, work: np.ndarray) -> np.ndarray:
        return np.concatenate([state.q[self.independent], state.qd[self.independent], work])

    def positions(self, t: float, q_independent: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """q with the dependent coordinates solved from C(q, t) = 0 (Newton from the anchor), and C_q
        there (the Jacobian of the last iterate, within round-off of the converged one's)."""
        system, dep, ind = self.system, self.dependent, self.independent
        start, start_jac, start_factors, start_c_t = self.start
        q = start.copy()
        if start_factors is not None:  # tangent predictor: C_D dq_D = -C_I dq_I (and -C_t dt)
            move = start_jac[:, ind] @ (q_independent - q[ind]) + system.c_t(t) - start_c_t
            q[dep] -= lu_solve(start_factors, move, check_finite=False)
        q[ind] = q_independent
        previous = np.inf
        for _ in range(NEWTON_STEPS):
            c, jac, _ = system.evaluate(q, t)
            residual = np.max(np.abs(c / system.row_scales), initial=0.0)
            factors = lu_factor(jac[:, dep], check_finite=False)
            stalled = residual < STALLED and residual > 0.5 * previous  # round-off reached
            previous = residual
            if residual <= RESIDUAL or stalled:
                self.q, self.jac, self.factors, self.c_t, self.t = q, jac, factors, system.c_t(t), t
                return q, jac
            q[dep] -= lu_solve(factors, c, check_finite=False)
        raise ConvergenceError(
            f"{system.scenario.name}: the dependent coordinates did not converge at t={t:.6g} "
            f"(constraint residual {residual:.2g})",
            time=t,
            q=q,
        )

    def state(self, t: float, y: np.ndarray) -> State:
        k = self.size
        q, jac = self.positions(t, y[:k])
        dep, ind = self.dependent, self.independent
        qd = np.empty_like(q)
        qd[ind] = y[k : 2 * k]
        rhs = -self.system.c_t(t) - jac[:, ind] @ qd[ind]
        qd[dep] = np.linalg.solve(jac[:, dep], rhs)
        q_d = self.system.q_d(q, qd, t)
        loads = self.loads(q, qd, t)
        qdd, lam = accelerations(jac, self.mass, loads.generalized, q_d)
        return State(t, q, qd, qdd, lam, jac, loads)

    def conditioning(self, jac: np.ndarray) -> float:
        """Reciprocal condition number (2-norm) of the scaled dependent block."""
        block = self.system.scaled_jacobian(jac)[:, self.dependent]
        s = np.linalg.svd(block, compute_uv=False)
        return float(s[-1] / s[0]) if s.size else 1.0

    def rates(self, t: float, y: np.ndarray) -> np.ndarray:
        self.evaluations += 1
        s = self.state(t, y)
        power = driver_power(self.system, s)
        return np.concatenate(
            [
                s.qd[self.independent],
                s.qdd[self.independent],
                [s.loads.applied_power, s.loads.dissipation, power],
            ]
        )


def driver_power(system: ConstraintSystem, s: State) -> float:
    """Power of the drivers' constraint forces, -lambda^T C_q q' over the driver rows."""
    rows = slice(int(system.offsets[len(system.scenario.joints)]), system.size)
    return float(-(s.lam[rows] @ (s.jac[rows] @ s.qd)))
