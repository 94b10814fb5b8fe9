"""Constrained dynamics in Pinocchio, integrated with RK4.

Each revolute loop closure is a Pinocchio `RigidConstraintModel` (CONTACT_3D between the two points;
the out-of-plane row is redundant, which the proximal solver tolerates) with Baumgarte gains kp, kd.
The drive is a constraint too: Pinocchio 4.1's `constraintDynamics` ignores a constraint's desired
acceleration, so the driver rows g(q) = f(t) get their Lagrange multipliers from the fact that the
constrained acceleration is affine in the joint force: with a0 = constraintDynamics(tau = 0) and
R_k = constraintDynamics(tau = J_k^T) - a0 for driver row k, a = a0 + R lambda where lambda solves
J R lambda = f'' - kp (g - f) - kd (g' - f') - drift - J a0.
"""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin
from scipy.linalg import lapack

from adapters.base import Diverged, EngineFailure, Singular
from adapters.pinocchio.model import PinModel, se3
from adapters.pinocchio.rows import Rows, Snapshot
from adapters.pinocchio.tree import Tree, point_pose
from scenarios.bodies import GROUND
from scenarios.joints import Revolute
from scenarios.scenario import Scenario

BLOWUP = 1e8
"""A joint speed above this (rad/s or m/s) counts as diverged."""


def dynamic_support(scenario: Scenario, tree: Tree) -> str | None:
    """None if every loop closure is a revolute joint, else why the dynamic mode cannot run it."""
    items = {j.name: j for j in scenario.joints}
    for name in tree.loops:
        item = items[name]
        if not isinstance(item, Revolute):
            return (
                f"dynamic mode: '{name}' is a {type(item).__name__} that closes a loop, and "
                "Pinocchio's constraintDynamics has constraint models for points and frames only "
                "(no gear, cam or sliding-line constraint; mimic joints are rejected there)"
            )
    return None


def _constraint(pm: PinModel, joint: Revolute, gains: tuple[float, float]) -> pin.RigidConstraintModel:
    placements = [point_pose(pm.tree, p) for p in (joint.p_i, joint.p_j)]
    ids = [0 if edge == GROUND else pm.joint_id[edge] for edge, _ in placements]
    cm = pin.RigidConstraintModel(
        pin.ContactType.CONTACT_3D,
        pm.model,
        ids[0],
        se3(placements[0][1]),
        ids[1],
        se3(placements[1][1]),
        pin.ReferenceFrame.LOCAL,
    )
    corrector = cm.m_baumgarte_parameters
    corrector.Kp, corrector.Kd = gains
    cm.m_baumgarte_parameters = corrector
    cm.name = joint.name
    return cm


class DynamicSolver:
    """RK4 on (q, v) with accelerations from `constraintDynamics` and the drive multipliers."""

    def __init__(self, pm: PinModel, rows: Rows, dt: float, gains: tuple[float, float]) -> None:
        if not dt > 0.0:
            raise EngineFailure(f"dt must be positive, got {dt}")
        self.pm, self.rows, self.dt, self.gains = pm, rows, dt, gains
        model = pm.model
        self.data, self.kin_data = model.createData(), model.createData()
        self.cmodels = pin.StdVec_RigidConstraintModel()
        for item in rows.loops:
            assert isinstance(item, Revolute)
            self.cmodels.append(_constraint(pm, item, gains))
        self.cdatas = pin.StdVec_RigidConstraintData()
        for cm in self.cmodels:
            self.cdatas.append(cm.createData())
        pin.initConstraintDynamics(model, self.data, self.cmodels, self.cdatas)
        self.prox = pin.ProximalSettings(1e-12, 1e-8, 10)
        self.empty = np.zeros(0)

    def _forward(self, q: np.ndarray, v: np.ndarray, tau: np.ndarray) -> np.ndarray:
        model = self.pm.model
        acc = pin.constraintDynamics(model, self.data, q, v, tau, self.cmodels, self.cdatas, self.prox)
        return np.array(acc, copy=True)

    def acceleration(self, t: float, q: np.ndarray, v: np.ndarray) -> np.ndarray:
        """The constrained acceleration with every driver row held to its prescribed motion."""
        a0 = self._forward(q, v, np.zeros_like(v))
        drive = self.rows.drive_rows(Snapshot(self.pm, self.kin_data, (q, v, self.empty, self.empty), 0))
        size, rows = drive.val.size, self.rows
        kp, kd = self.gains
        wanted = rows.targets(size, t, 2) - drive.drift - drive.jac @ a0
        if kp or kd:
            wanted -= kp * (drive.val - rows.targets(size, t, 0))
            wanted -= kd * (drive.rate - rows.targets(size, t, 1))
        response = np.array([self._forward(q, v, row) for row in drive.jac]).T - a0[:, None]
        _, _, multipliers, info = lapack.dgesv(drive.jac @ response, wanted)
        if info != 0:
            raise Singular(f"the drive cannot be held by constraint forces at t = {t:.6g}", t)
        return a0 + response @ multipliers

    def run(
        self, q0: np.ndarray, v0: np.ndarray, times: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, int]:
        """q, v, a at every output time and the number of RK4 steps taken."""
        n = len(times)
        out = np.zeros((3, n, q0.size))
        q, v = q0.copy(), v0.copy()
        a = self.acceleration(float(times[0]), q, v)
        out[:, 0] = q, v, a
        steps = 0
        for k in range(1, n):
            start, interval = float(times[k - 1]), float(times[k] - times[k - 1])
            substeps = max(1, math.ceil(interval / self.dt - 1e-9))
            h = interval / substeps
            for i in range(substeps):
                t = start + i * h
                q, v, a = self._step(t, h, q, v, a)
                if not (np.all(np.isfinite(a)) and np.max(np.abs(v)) < BLOWUP):
                    raise Diverged(f"RK4 with constraintDynamics diverged at t = {t + h:.6g}", t + h)
            steps += substeps
            out[:, k] = q, v, a
        return out[0], out[1], out[2], steps

    def _step(
        self, t: float, h: float, q: np.ndarray, v: np.ndarray, a: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """One RK4 step from (q, v) with acceleration a; returns the new state and its acceleration."""
        q2, v2 = q + 0.5 * h * v, v + 0.5 * h * a
        a2 = self.acceleration(t + 0.5 * h, q2, v2)
        q3, v3 = q + 0.5 * h * v2, v + 0.5 * h * a2
        a3 = self.acceleration(t + 0.5 * h, q3, v3)
        q4, v4 = q + h * v3, v + h * a3
        a4 = self.acceleration(t + h, q4, v4)
        q_new = q + h / 6.0 * (v + 2.0 * v2 + 2.0 * v3 + v4)
        v_new = v + h / 6.0 * (a + 2.0 * a2 + 2.0 * a3 + a4)
        return q_new, v_new, self.acceleration(t + h, q_new, v_new)
