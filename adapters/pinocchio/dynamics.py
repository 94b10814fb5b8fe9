"""Constrained dynamics in Pinocchio under the scenario's loads, marched by RK4 or semi-implicit Euler.

Each revolute loop closure is a Pinocchio `RigidConstraintModel` (CONTACT_3D between the two points;
the out-of-plane row is redundant, which the proximal solver tolerates) with Baumgarte gains kp, kd.
The drive is a constraint too: Pinocchio 4.1's `constraintDynamics` ignores a constraint's desired
acceleration, so the driver rows g(q) = f(t) get their Lagrange multipliers from the fact that the
constrained acceleration is affine in the joint force: with a0 = constraintDynamics(tau) (tau the
loads' joint torques) and R_k = constraintDynamics(tau + J_k^T) - a0 for driver row k,
a = a0 + R lambda where lambda solves J R lambda = f'' - kp (g - f) - kd (g' - f') - drift - J a0.
A mechanism without loops (a tree) takes Pinocchio's articulated-body algorithm `aba` instead.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin
from scipy.linalg import lapack

from adapters.base import EngineFailure, Singular
from adapters.pinocchio.constraint_rows import ConstraintRows, Snapshot
from adapters.pinocchio.loads import Loads
from adapters.pinocchio.model import PinModel, se3
from adapters.pinocchio.simulation import RK4, march
from adapters.pinocchio.tree import Tree, point_pose
from scenarios.bodies import GROUND
from scenarios.joints import Revolute
from scenarios.scenario import Scenario


def dynamic_support(scenario: Scenario, tree: Tree) -> str | None:
    """None if every loop closure is a revolute joint, else why the dynamic mode cannot run it."""
    items = {j.name: j for j in scenario.joints}
    for name in tree.closures:
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
        pin.ReferenceFrame.LOCAL_WORLD_ALIGNED,
    )
    corrector = cm.m_baumgarte_parameters
    corrector.Kp, corrector.Kd = gains
    cm.m_baumgarte_parameters = corrector
    cm.name = joint.name
    return cm


class DynamicSolver:
    """Accelerations from `constraintDynamics` (or `aba` on a tree) under the scenario's loads, with
    the drive multipliers, marched by RK4 or semi-implicit Euler (adapters.pinocchio.simulation)."""

    def __init__(
        self,
        pm: PinModel,
        constraint_rows: ConstraintRows,
        dt: float,
        gains: tuple[float, float],
        loads: Loads | None = None,
        method: str = RK4,
    ) -> None:
        if not dt > 0.0:
            raise EngineFailure(f"dt must be positive, got {dt}")
        self.pm, self.constraint_rows, self.dt, self.gains, self.loads, self.method = (
            pm,
            constraint_rows,
            dt,
            gains,
            loads,
            method,
        )
        model = pm.model
        self.data, self.kin_data = model.createData(), model.createData()
        self.cmodels = pin.StdVec_RigidConstraintModel()
        for item in constraint_rows.closures:
            assert isinstance(item, Revolute)
            self.cmodels.append(_constraint(pm, item, gains))
        self.cdatas = pin.StdVec_RigidConstraintData()
        for cm in self.cmodels:
            self.cdatas.append(cm.createData())
        if self.cmodels:
            pin.initConstraintDynamics(model, self.data, self.cmodels, self.cdatas)
        self.prox = pin.ProximalSettings(1e-12, 1e-8, 10)
        self.empty = np.zeros(0)

    def tau(self, t: float, q: np.ndarray, v: np.ndarray) -> np.ndarray:
        """The joint torques of the applied loads (zero without loads)."""
        return np.zeros(self.pm.model.nv) if self.loads is None else self.loads.generalized(t, q, v)

    def _forward(self, q: np.ndarray, v: np.ndarray, tau: np.ndarray) -> np.ndarray:
        model = self.pm.model
        if not self.cmodels:  # a tree: Pinocchio's articulated-body algorithm
            return pin.aba(model, self.data, q, v, tau).copy()  # type: ignore[no-any-return]
        acc = pin.constraintDynamics(model, self.data, q, v, tau, self.cmodels, self.cdatas, self.prox)
        return acc.copy()  # type: ignore[no-any-return]

    def acceleration(self, t: float, q: np.ndarray, v: np.ndarray) -> np.ndarray:
        """The constrained acceleration with every driver row held to its prescribed motion."""
        return self._driven(t, q, v)[0]

    def _driven(self, t: float, q: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The acceleration and the drive rows' forces mu: the drives apply tau + J^T mu."""
        tau = self.tau(t, q, v)
        a0 = self._forward(q, v, tau)
        if not self.constraint_rows.drivers:
            return a0, self.empty
        drive = self.constraint_rows.drive_rows(
            Snapshot(self.pm, self.kin_data, (q, v, self.empty, self.empty), 0)
        )
        size, constraint_rows = drive.val.size, self.constraint_rows
        kp, kd = self.gains
        wanted = constraint_rows.targets(size, t, 2) - drive.drift - drive.jac @ a0
        if kp or kd:
            wanted -= kp * (drive.val - constraint_rows.targets(size, t, 0))
            wanted -= kd * (drive.rate - constraint_rows.targets(size, t, 1))
        response = np.array([self._forward(q, v, tau + row) for row in drive.jac]).T - a0[:, None]
        _, _, multipliers, info = lapack.dgesv(drive.jac @ response, wanted)
        if info != 0:
            raise Singular(f"the drive cannot be held by constraint forces at t = {t:.6g}", t)
        return a0 + response @ multipliers, multipliers

    def move(self, q: np.ndarray, dq: np.ndarray) -> np.ndarray:
        """Pinocchio's configuration update q (+) dq."""
        return np.asarray(pin.integrate(self.pm.model, q, dq))

    def run(
        self, q0: np.ndarray, v0: np.ndarray, times: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, int]:
        """q, v, a at every output time and the number of steps taken."""
        start = (q0.copy(), v0.copy(), self.acceleration(float(times[0]), q0, v0))
        return march(self.acceleration, self.move, start, times, self.dt, self.method)
