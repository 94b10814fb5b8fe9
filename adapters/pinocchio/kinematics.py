"""Kinematic analysis on Pinocchio's model: Newton on the loop-closure and driver rows for the
position, then the velocity and acceleration from the same Jacobian and Pinocchio's classical
accelerations. The unknowns are z = [q ; phi] (joint coordinates, then cam contact parameters).

Sizes are relative to the mechanism: an unknown's size is 1 for an angle (revolute joints, cam
parameters) and the characteristic length for a slide; a row's size is the largest of its
Jacobian entries times the unknowns' sizes at the assembly guess (a loop closure is a length, a
driven angle an angle, a roller's rows lengths squared). Residuals are measured in row sizes,
steps in unknown sizes, so that the Newton tolerance means the same on a 1e-4 m and a 1e3 m
mechanism."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pinocchio as pin

from adapters.base import EngineFailure, Singular
from adapters.pinocchio.constraint_rows import LWA, ConstraintRows, Snapshot
from adapters.pinocchio.linalg import SINGULAR_COND, Factor, factorize, solve
from adapters.pinocchio.model import PinModel
from adapters.pinocchio.quantity import Quantity
from scenarios.bodies import Point

ROUNDOFF = 4.0 * np.finfo(float).eps
"""A Newton step this small relative to z (and its size) cannot reduce the residual further..."""
FLOOR = 1e-9
"""...if the residual is already this small (in row sizes): then Newton stops above a tolerance
below rounding."""
HALVINGS = 20
"""How often an output interval may be halved to follow the branch or locate a singularity."""
JUMP = 0.5
"""Newton's solution may lie at most this fraction of the predictor's own move from the predictor
(plus JUMP_FLOOR, in unknown sizes); farther, it has likely landed on another branch..."""
JUMP_FLOOR = 1e-6
"""...so the step is halved, and a jump that persists over a tiny step is reported, not taken."""

State = tuple[np.ndarray, np.ndarray, np.ndarray]
"""z, z' and z''."""


@dataclass
class KinematicSolver:
    """Position, velocity and acceleration of a kinematically driven mechanism at given times."""

    pm: PinModel
    constraint_rows: ConstraintRows
    tol: float = 1e-13
    max_iter: int = 25
    length: float = 1.0
    """The characteristic length: the size of a slide's coordinate."""
    data: pin.Data = field(init=False)
    cams: int = field(init=False)
    sizes: np.ndarray = field(init=False)
    _row_sizes: np.ndarray | None = field(init=False, default=None)

    def __post_init__(self) -> None:
        self.data = self.pm.model.createData()
        self.cams = len(self.constraint_rows.contacts)
        self.sizes = np.ones(self.pm.model.nq + self.cams)
        for edge in self.pm.tree.edges:
            k = self.pm.q_index(edge.name) if edge.kind == "prismatic" else None
            if k is not None:
                self.sizes[k] = self.length

    def row_sizes(self, jac: np.ndarray) -> np.ndarray:
        """Each row's size: its largest Jacobian entry times the unknown's size (1 for a null row),
        taken at the first configuration solved (the assembly guess) and kept: a row's Jacobian
        shrinks near a singular configuration, its units do not."""
        if self._row_sizes is None or self._row_sizes.size != jac.shape[0]:
            size = np.abs(jac * self.sizes[None, :]).max(axis=1, initial=0.0)
            self._row_sizes = np.where(size > 0.0, size, 1.0)
        return self._row_sizes

    def snapshot(self, z: np.ndarray, z_rate: np.ndarray | None = None) -> Snapshot:
        nq = self.pm.model.nq
        rate = np.zeros_like(z) if z_rate is None else z_rate
        return Snapshot(self.pm, self.data, (z[:nq], rate[:nq], z[nq:], rate[nq:]), self.cams)

    def _system(self, z: np.ndarray, t: float) -> tuple[Quantity, np.ndarray]:
        rows = self.constraint_rows.evaluate(self.snapshot(z))
        return rows, rows.val - self.constraint_rows.targets(rows.val.size, t, 0)

    def position(self, z: np.ndarray, t: float, max_iter: int | None = None) -> tuple[np.ndarray, Factor]:
        """Newton from the guess z; the factorized row Jacobian at the solution."""
        z = z.copy()
        limit = self.max_iter if max_iter is None else max_iter
        for iteration in range(limit + 1):
            rows, gap = self._system(z, t)
            if not np.all(np.isfinite(gap)):
                raise EngineFailure(f"non-finite constraint residual at t = {t:.6g}", t)
            residual = float(np.max(np.abs(gap) / self.row_sizes(rows.jac)))
            if residual <= self.tol:
                return z, factorize(rows.jac, t)
            if iteration == limit:
                break
            step = solve(rows.jac, -gap)
            if step is None:
                raise Singular(f"singular constraint Jacobian at t = {t:.6g}", t)
            if residual <= FLOOR and self._scaled(step) <= ROUNDOFF * (1.0 + self._scaled(z)):
                return z, factorize(rows.jac, t)  # the residual has reached its rounding floor
            z += step
        factorize(rows.jac, t, SINGULAR_COND / 100.0)  # near-singular: that explains the failure
        raise EngineFailure(
            f"Newton did not converge at t = {t:.6g} (residual {residual:.3g} of the rows' sizes after "
            f"{limit} iterations)",
            t,
        )

    def rates(self, z: np.ndarray, factor: Factor, t: float) -> tuple[np.ndarray, np.ndarray]:
        """z' from J z' = f', then z'' from J z'' = f'' - drift with the drift at (z, z')."""
        size = z.size
        z_rate = factor.solve(self.constraint_rows.targets(size, t, 1))
        moving = self.constraint_rows.evaluate(self.snapshot(z, z_rate))
        z_acc = factor.solve(self.constraint_rows.targets(size, t, 2) - moving.drift)
        return z_rate, z_acc

    def assemble(self, z_guess: np.ndarray, t: float) -> np.ndarray:
        """The configuration at t from a rough guess (more iterations allowed)."""
        try:
            z, _ = self.position(z_guess, t, max_iter=4 * self.max_iter)
        except EngineFailure as failure:
            raise type(failure)(f"cannot assemble at t = {t:.6g}: {failure}", t) from None
        return z

    def run(self, z0: np.ndarray, times: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """z, z' and z'' at every time, each solve starting from the previous one's Taylor guess."""
        out = np.zeros((3, len(times), z0.size))
        z, factor = self.position(z0, float(times[0]))
        state = (z, *self.rates(z, factor, float(times[0])))
        sign = factor.det_sign
        out[:, 0] = state
        for k in range(1, len(times)):
            state, sign = self._advance(state, sign, float(times[k - 1]), float(times[k]), 0)
            out[:, k] = state
        return out[0], out[1], out[2]

    def jump(self, z: np.ndarray, predicted: np.ndarray, z1: np.ndarray) -> float:
        """How far Newton's solution z1 lies from the predictor, in units of the allowed distance:
        JUMP times the predictor's own move from z, plus JUMP_FLOOR (all in unknown sizes)."""
        return self._scaled(z1 - predicted) / (JUMP * self._scaled(predicted - z) + JUMP_FLOOR)

    def _scaled(self, dz: np.ndarray) -> float:
        """The largest entry of dz in unknown sizes."""
        return float(np.max(np.abs(dz) / self.sizes, initial=0.0))

    def _advance(self, state: State, sign: float, t0: float, t1: float, depth: int) -> tuple[State, float]:
        """The solution at t1 from the one at t0 on the same assembly branch.

        The sign of det J is followed: when it changes, when Newton fails, or when it lands far from
        the predictor (`jump`), the interval is halved, so that a poor guess over a long step cannot
        land on another branch unnoticed; a change or a jump that persists over a tiny interval is
        reported as a singular configuration there.
        """
        z, z_rate, z_acc = state
        h = t1 - t0
        predicted = z + h * z_rate + 0.5 * h * h * z_acc
        try:
            z1, factor = self.position(predicted, t1)
        except Singular:
            raise
        except EngineFailure:
            if depth >= HALVINGS:
                raise
        else:
            jump = self.jump(z, predicted, z1)
            if factor.det_sign == sign and jump <= 1.0:
                return (z1, *self.rates(z1, factor, t1)), sign
            if depth >= HALVINGS and factor.det_sign != sign:
                raise Singular(
                    f"the constraint Jacobian's determinant changes sign between t = {t0:.9g} and "
                    f"t = {t1:.9g}: a singular configuration lies between",
                    t1,
                )
            if depth >= HALVINGS:
                raise Singular(
                    f"Newton lands {jump:.3g} times farther from the predictor than allowed between "
                    f"t = {t0:.9g} and t = {t1:.9g}, after {depth} halvings of the step: the branch "
                    "cannot be followed (another closure passes close)",
                    t1,
                )
        middle = 0.5 * (t0 + t1)
        half, sign = self._advance(state, sign, t0, middle, depth + 1)
        return self._advance(half, sign, middle, t1, depth + 1)


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
