"""Kinematic analysis on Pinocchio's model: Newton on the loop-closure and driver rows for the
position, then the velocity and acceleration from the same Jacobian and Pinocchio's classical
accelerations. The unknowns are z = [q ; phi] (joint coordinates, then cam contact parameters)."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pinocchio as pin
from scipy.linalg import lapack

from adapters.base import EngineFailure, Singular
from adapters.pinocchio_model import PinModel
from adapters.pinocchio_quantity import Quantity
from adapters.pinocchio_rows import LWA, Rows, Snapshot
from scenarios.bodies import Point

SINGULAR_COND = 1e10
"""Condition number of the row Jacobian above which a configuration counts as singular."""
ROUNDOFF = 4.0 * np.finfo(float).eps
"""A Newton step this small relative to z cannot reduce the residual further..."""
FLOOR = 1e-9
"""...if the residual is already this small: then Newton stops above a tolerance below rounding."""

Factor = tuple[np.ndarray, np.ndarray]
"""An LU factorization (LAPACK getrf: factors and pivots)."""


def _solve(jac: np.ndarray, rhs: np.ndarray) -> tuple[np.ndarray, int]:
    _, _, x, info = lapack.dgesv(jac, rhs)
    return x, int(info)


def _back(lu: np.ndarray, pivots: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    return np.asarray(lapack.dgetrs(lu, pivots, rhs)[0])


def _det_sign(factor: Factor) -> float:
    lu, pivots = factor
    swaps = np.count_nonzero(pivots != np.arange(pivots.size))
    return float(np.prod(np.sign(np.diag(lu)))) * (-1.0) ** swaps


def factorize(jac: np.ndarray, t: float, bound: float = SINGULAR_COND) -> Factor:
    """LU of the row Jacobian; Singular if its estimated condition number exceeds `bound`."""
    lu, pivots, info = lapack.dgetrf(jac)
    rcond = lapack.dgecon(lu, np.abs(jac).sum(axis=0).max())[0] if info == 0 else 0.0
    if not rcond * bound > 1.0:
        cond = f"{1.0 / rcond:.3g}" if rcond > 0.0 else "infinite"
        raise Singular(f"constraint Jacobian is singular at t = {t:.6g} (condition {cond})", t)
    return lu, pivots


@dataclass
class KinematicSolver:
    """Position, velocity and acceleration of a kinematically driven mechanism at given times."""

    pm: PinModel
    rows: Rows
    tol: float = 1e-13
    max_iter: int = 25
    data: pin.Data = field(init=False)
    cams: int = field(init=False)

    def __post_init__(self) -> None:
        self.data = self.pm.model.createData()
        self.cams = len(self.rows.contacts)

    def snapshot(self, z: np.ndarray, z_rate: np.ndarray | None = None) -> Snapshot:
        nq = self.pm.model.nq
        rate = np.zeros_like(z) if z_rate is None else z_rate
        return Snapshot(self.pm, self.data, (z[:nq], rate[:nq], z[nq:], rate[nq:]), self.cams)

    def _system(self, z: np.ndarray, t: float) -> tuple[Quantity, np.ndarray]:
        rows = self.rows.evaluate(self.snapshot(z))
        return rows, rows.val - self.rows.targets(rows.val.size, t, 0)

    def position(self, z: np.ndarray, t: float, max_iter: int | None = None) -> tuple[np.ndarray, Factor]:
        """Newton from the guess z; the factorized row Jacobian at the solution."""
        z = z.copy()
        limit = self.max_iter if max_iter is None else max_iter
        for iteration in range(limit + 1):
            rows, gap = self._system(z, t)
            if not np.all(np.isfinite(gap)):
                raise EngineFailure(f"non-finite constraint residual at t = {t:.6g}", t)
            residual = np.max(np.abs(gap))
            if residual <= self.tol:
                return z, factorize(rows.jac, t)
            if iteration == limit:
                break
            step, info = _solve(rows.jac, -gap)
            if info != 0:
                raise Singular(f"singular constraint Jacobian at t = {t:.6g}", t)
            if residual <= FLOOR and np.max(np.abs(step)) <= ROUNDOFF * (1.0 + np.max(np.abs(z))):
                return z, factorize(rows.jac, t)  # the residual has reached its rounding floor
            z += step
        factorize(rows.jac, t, 1e8)
        raise EngineFailure(
            f"Newton did not converge at t = {t:.6g} (residual {residual:.3g} after {limit} iterations)",
            t,
        )

    def rates(self, z: np.ndarray, factor: Factor, t: float) -> tuple[np.ndarray, np.ndarray]:
        """z' from J z' = f', then z'' from J z'' = f'' - drift with the drift at (z, z')."""
        lu, pivots = factor
        size = lu.shape[0]
        z_rate = _back(lu, pivots, self.rows.targets(size, t, 1))
        moving = self.rows.evaluate(self.snapshot(z, z_rate))
        z_acc = _back(lu, pivots, self.rows.targets(size, t, 2) - moving.drift)
        return z_rate, z_acc

    def assemble(self, z_guess: np.ndarray, t: float) -> np.ndarray:
        """The configuration at t from a rough guess (more iterations allowed)."""
        try:
            z, _ = self.position(z_guess, t, max_iter=4 * self.max_iter)
        except EngineFailure as failure:
            raise type(failure)(f"cannot assemble at t = {t:.6g}: {failure}", t) from None
        return z

    def run(self, z0: np.ndarray, times: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """z, z' and z'' at every time; each solve starts from the previous step's Taylor guess.

        The sign of det J is followed: a change between two time points means the path crossed a
        singular configuration (or Newton jumped to another assembly branch), reported as Singular.
        """
        n = z0.size
        out = np.zeros((3, len(times), n))
        z, z_rate, z_acc = z0, np.zeros(n), np.zeros(n)
        sign = 0.0
        for k, t in enumerate(times):
            h = t - times[k - 1] if k else 0.0
            z, factor = self.position(z + h * z_rate + 0.5 * h * h * z_acc, float(t))
            if sign and _det_sign(factor) != sign:
                raise Singular(
                    f"the constraint Jacobian's determinant changes sign between t = {times[k - 1]:.6g} "
                    f"and t = {t:.6g}: a singular configuration lies between",
                    float(t),
                )
            sign = _det_sign(factor)
            z_rate, z_acc = self.rates(z, factor, float(t))
            out[:, k] = z, z_rate, z_acc
        return out[0], out[1], out[2]


def body_motion(
    pm: PinModel, data: pin.Data, state: tuple[np.ndarray, np.ndarray, np.ndarray], bodies: tuple[str, ...]
) -> np.ndarray:
    """(3 levels, bodies, 3) canonical pose, velocity and acceleration of `bodies` from Pinocchio's
    frame placements, frame velocities and classical frame accelerations."""
    q, v, a = state
    pin.forwardKinematics(pm.model, data, q, v, a)
    out = np.zeros((3, len(bodies), 3))
    for k, body in enumerate(bodies):
        fid = pm.frame_id[Point(body)]
        placement = pin.updateFramePlacement(pm.model, data, fid)
        velocity = pin.getFrameVelocity(pm.model, data, fid, LWA)
        acceleration = pin.getFrameClassicalAcceleration(pm.model, data, fid, LWA)
        out[0, k] = (*placement.translation[:2], pm.angle(body, q))
        out[1, k] = (*velocity.linear[:2], velocity.angular[2])
        out[2, k] = (*acceleration.linear[:2], acceleration.angular[2])
    return out
