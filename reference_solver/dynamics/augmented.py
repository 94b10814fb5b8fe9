"""The augmented equations of motion, [M C_q^T; C_q 0] [q''; lambda] = [Q_e; Q_d], and what the
multipliers mean: -C_q^T lambda is the constraint force, so a joint's rows give its reaction and a
driver's rows its driving force or torque."""

from __future__ import annotations

import warnings

import numpy as np
from scipy.linalg import LinAlgWarning, lu_factor, lu_solve

from reference_solver.system import ConstraintSystem
from scenarios.bodies import GROUND
from scenarios.drivers import Driver
from scenarios.joints import Prismatic, Revolute, RevoluteRevolute


def accelerations(
    jac: np.ndarray, mass: np.ndarray, q_e: np.ndarray, q_d: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """q'' and lambda from the augmented system at one state (dense LU of the saddle-point matrix).

    Rows of C_q are scaled to unit length first (lambda is scaled back), so the solve is as well
    conditioned in metres as in millimetres.
    """
    n, m = mass.size, jac.shape[0]
    norms = np.linalg.norm(jac, axis=1)
    norms[norms == 0.0] = 1.0
    scaled = jac / norms[:, None]
    kkt = np.zeros((n + m, n + m))
    kkt[:n, :n] = np.diag(mass)
    kkt[:n, n:] = scaled.T
    kkt[n:, :n] = scaled
    with warnings.catch_warnings():
        warnings.simplefilter("error", LinAlgWarning)
        factors = lu_factor(kkt, check_finite=False)
    solution = lu_solve(factors, np.concatenate([q_e, q_d / norms]), check_finite=False)
    return solution[:n], solution[n:] / norms


def constraint_outputs(system: ConstraintSystem, jac: np.ndarray, lam: np.ndarray) -> dict[str, float]:
    """Joint reactions `<joint>.fx/.fy` (the force the joint applies to its first moving body, global
    axes) and driving forces `<driver>.force` (minus the multiplier: the generalized force the driver
    applies along its coordinate; `<row>.force` for drivers of several rows)."""
    out: dict[str, float] = {}
    constraints = (*system.scenario.joints, *system.scenario.drivers)
    for constraint, eq, start in zip(constraints, system.equations, system.offsets, strict=False):
        rows = slice(int(start), int(start) + eq.size)
        if isinstance(constraint, Driver):
            if eq.size == 1:
                out[f"{eq.name}.force"] = -float(lam[rows][0])
            else:
                for label, value in zip(eq.labels, lam[rows], strict=True):
                    out[f"{label}.force"] = -float(value)
            continue
        if not isinstance(constraint, Revolute | Prismatic | RevoluteRevolute):
            continue
        moving = [p.body for p in (constraint.p_i, constraint.p_j) if p.body != GROUND]
        col = system.layout.body_column(moving[0])
        assert col is not None
        force = -(jac[rows, col : col + 2].T @ lam[rows])
        out[f"{eq.name}.fx"], out[f"{eq.name}.fy"] = float(force[0]), float(force[1])
    return out
