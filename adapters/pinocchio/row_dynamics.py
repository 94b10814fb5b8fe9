"""Constrained dynamics on any constraint rows: `pin.forwardDynamics` with the adapter's rows.

Pinocchio's constraint models are points and frames; a gear, a rack or a sliding line is none of
them. But `pin.forwardDynamics(model, data, q, v, tau, J, gamma)` solves M a - J^T lambda = tau - b
with J a = -gamma for any rows J: here every row the tree does not satisfy (gear and rack couplings,
loop closures, drivers), with gamma = drift - f'' + kp (g - f) + kd (g' - f') so that the rows'
accelerations follow the prescribed motion (Baumgarte gains kp, kd). Pinocchio computes the
dynamics (computeAllTerms, the KKT solve) under the loads' joint torques; the adapter supplies the
rows and marches with RK4 or semi-implicit Euler.
Cam contacts add the contact parameter phi, an unknown outside Pinocchio's q: CamDynamicSolver
(adapters.pinocchio.cam_dynamics) eliminates it.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pinocchio as pin

from adapters.base import Singular
from adapters.pinocchio.constraint_rows import ConstraintRows, Snapshot
from adapters.pinocchio.dynamics import DynamicSolver
from adapters.pinocchio.model import PinModel
from adapters.pinocchio.quantity import Quantity


class RowDynamicSolver(DynamicSolver):
    """RK4 on (q, v) with accelerations from `pin.forwardDynamics` on the stacked rows."""

    def __init__(self, pm: PinModel, constraint_rows: ConstraintRows, *args: Any, **kwargs: Any) -> None:
        """As DynamicSolver (dt, gains, loads, method), the drive rows held by forwardDynamics too."""
        super().__init__(
            pm, ConstraintRows((), constraint_rows.drivers, {}, constraint_rows.motions), *args, **kwargs
        )
        self.all_constraint_rows = constraint_rows

    def wanted(self, rows: Quantity, t: float) -> np.ndarray:
        """The rows' wanted accelerations J z'' = f'' - drift - kp (g - f) - kd (g' - f')."""
        size = rows.val.size
        kp, kd = self.gains
        wanted = self.all_constraint_rows.targets(size, t, 2) - rows.drift
        if kp or kd:
            wanted -= kp * (rows.val - self.all_constraint_rows.targets(size, t, 0))
            wanted -= kd * (rows.rate - self.all_constraint_rows.targets(size, t, 1))
        return wanted

    def forward(
        self, t: float, q: np.ndarray, v: np.ndarray, jac: np.ndarray, wanted: np.ndarray
    ) -> np.ndarray:
        """Pinocchio's forwardDynamics with rows jac q'' = wanted."""
        try:
            acc = pin.forwardDynamics(self.pm.model, self.data, q, v, self.tau(t, q, v), jac, -wanted, 0.0)
        except RuntimeError as error:
            raise Singular(f"forwardDynamics failed at t = {t:.6g}: {error}", t) from error
        return acc.copy()  # type: ignore[no-any-return]

    def acceleration(self, t: float, q: np.ndarray, v: np.ndarray) -> np.ndarray:
        rows = self.all_constraint_rows.evaluate(
            Snapshot(self.pm, self.kin_data, (q, v, self.empty, self.empty), 0)
        )
        return self.forward(t, q, v, rows.jac, self.wanted(rows, t))
