"""Constrained dynamics of a cam mechanism in Pinocchio: the contact parameters eliminated.

A cam contact adds an unknown phi (where on the profile the follower touches) and two rows
g(q, phi) = 0; Pinocchio's forwardDynamics takes rows on q only. At each evaluation phi is solved
from the contact rows for the current q (Gauss-Newton on g, warm-started from the last phi), phi'
from the velocity rows, and every row is projected onto the left null space N of dg/dphi: then
N^T (dg/dq) q'' = N^T (f'' - drift) has no phi'' in it, and N^T g = 0 is the contact condition on q
alone (for a roller: the centre at distance r from the profile). forwardDynamics gets these rows
with the Baumgarte terms on N^T (g - f) and N^T (g' - f').
"""

from __future__ import annotations

import numpy as np
from scipy.linalg import null_space

from adapters.base import EngineFailure
from adapters.pinocchio.kinematics import KinematicSolver
from adapters.pinocchio.row_dynamics import RowDynamicSolver

NEWTON = 20
"""Gauss-Newton steps at most for phi at one evaluation."""
PHI_TOL = 1e-14
"""A phi step this small (radians of profile parameter) has converged..."""
PHI_FLOOR = 1e-10
"""...and one this small that no longer halves has reached the rows' rounding."""


class CamDynamicSolver(RowDynamicSolver):
    """forwardDynamics on the rows projected past the cam contact parameters."""

    last: tuple[np.ndarray, np.ndarray] | None
    """(q, row Jacobian) of the last contact solve, the predictor's base."""

    def __init__(
        self, kinematics: KinematicSolver, phi0: np.ndarray, *args: object, **kwargs: object
    ) -> None:
        super().__init__(kinematics.pm, kinematics.constraint_rows, *args, **kwargs)  # type: ignore[arg-type]
        self.kinematics = kinematics
        self.restart(phi0)

    def restart(self, phi0: np.ndarray) -> None:
        """Start the contact parameters' warm start afresh from phi0 (each run from the start)."""
        self.phi = phi0.copy()
        self.last = None

    def solve_phi(self, q: np.ndarray, t: float) -> np.ndarray:
        """The contact parameters that close the contact rows best (least squares) at q."""
        return self._contact(q, t)[0]

    def _contact(self, q: np.ndarray, t: float) -> tuple[np.ndarray, np.ndarray]:
        """(phi, the row Jacobian at phi) by Gauss-Newton from the last phi; the Jacobian is the last
        iteration's, taken at most a rounding-sized step from phi."""
        nq, phi, previous = q.size, self.phi, np.inf
        if self.last is not None:  # first-order predictor along the last Jacobian
            q_last, jac_last = self.last
            phi = phi - np.linalg.lstsq(jac_last[:, nq:], jac_last[:, :nq] @ (q - q_last), rcond=None)[0]
        for _ in range(NEWTON):
            rows = self.all_constraint_rows.evaluate(self.kinematics.snapshot(np.concatenate([q, phi])))
            gap = rows.val - self.all_constraint_rows.targets(rows.val.size, t, 0)
            step = np.linalg.lstsq(rows.jac[:, nq:], -gap, rcond=None)[0]
            size = float(np.max(np.abs(step)))
            if size > 0.5 * previous and size <= PHI_FLOOR:  # no longer converging: at rounding
                break
            phi, previous = phi + step, size
            if size <= PHI_TOL:
                break
        else:
            raise EngineFailure(f"the cam contact parameter does not converge at t = {t:.6g}", t)
        self.phi, self.last = phi, (q.copy(), rows.jac)
        return phi, rows.jac

    def acceleration(self, t: float, q: np.ndarray, v: np.ndarray) -> np.ndarray:
        nq = q.size
        phi, jac = self._contact(q, t)
        size = jac.shape[0]
        jq, jphi = jac[:, :nq], jac[:, nq:]
        phi_rate = np.linalg.lstsq(jphi, self.all_constraint_rows.targets(size, t, 1) - jq @ v, rcond=None)[0]
        state = np.concatenate([q, phi]), np.concatenate([v, phi_rate])
        rows = self.all_constraint_rows.evaluate(self.kinematics.snapshot(*state))
        jq, jphi = rows.jac[:, :nq], rows.jac[:, nq:]
        project = null_space(jphi.T).T  # N^T: N^T dg/dphi = 0
        return self.forward(t, q, v, project @ jq, project @ self.wanted(rows, t))
