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


def output_rows(system: ConstraintSystem) -> tuple[list[tuple[str, int]], list[tuple[str, slice, int]]]:
    """Where each output of `constraint_outputs` comes from: each driver row's force column and row
    ('<driver>.force', or '<row>.force' for drivers of several rows), and each joint's name, rows
    and the first column of its first moving body (whose x and y rows give the reaction)."""
    drivers: list[tuple[str, int]] = []
    joints: list[tuple[str, slice, int]] = []
    constraints = (*system.scenario.joints, *system.scenario.drivers)
    for constraint, eq, start in zip(constraints, system.equations, system.offsets, strict=False):
        first = int(start)
        if isinstance(constraint, Driver):
            labels = [eq.name] if eq.size == 1 else list(eq.labels)
            drivers += [(f"{label}.force", first + k) for k, label in enumerate(labels)]
            continue
        if not isinstance(constraint, Revolute | Prismatic | RevoluteRevolute):
            continue
        moving = [p.body for p in (constraint.p_i, constraint.p_j) if p.body != GROUND]
        col = system.layout.body_column(moving[0])
        assert col is not None
        joints.append((eq.name, slice(first, first + eq.size), col))
    return drivers, joints


def constraint_outputs(system: ConstraintSystem, jac: np.ndarray, lam: np.ndarray) -> dict[str, float]:
    """Joint reactions `<joint>.fx/.fy` (the force the joint applies to its first moving body, global
    axes) and driving forces `<driver>.force` (minus the multiplier: the generalized force the driver
    applies along its coordinate; `<row>.force` for drivers of several rows)."""
    drivers, joints = output_rows(system)
    out: dict[str, float] = {}
    for name, rows, col in joints:  # the joints' rows come before the drivers'
        force = -(jac[rows, col : col + 2].T @ lam[rows])
        out[f"{name}.fx"], out[f"{name}.fy"] = float(force[0]), float(force[1])
    out.update({name: -float(lam[row]) for name, row in drivers})
    return out
