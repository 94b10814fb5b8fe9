"""Small dense solves for the kinematic mode: LAPACK LU of the equilibrated row Jacobian, its
condition estimate (the singularity test) and the sign of its determinant (the branch test)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.linalg import lapack

from adapters.base import Singular

SINGULAR_COND = 1e6
"""Estimated condition number of the equilibrated row Jacobian above which a configuration counts
as singular. Regular configurations of the catalogue stay below 30; Newton, which converges only
linearly onto a singular configuration, stops about 1e-7 from it, where the estimate exceeds 1e7."""
EQUILIBRATION_FLOOR = 1e-3
"""Rows and columns are scaled to unit size, but never by more than 1 / this times the largest, so
that a row that vanishes at a singular configuration is not inflated back to unit size."""


def solve(jac: np.ndarray, rhs: np.ndarray) -> np.ndarray | None:
    """J x = rhs, or None if J is exactly singular."""
    _, _, x, info = lapack.dgesv(jac, rhs)
    return None if info != 0 else np.asarray(x)


@dataclass(frozen=True)
class Factor:
    """LU of S = R J C, with R and C the diagonal row and column scalings that equilibrate J."""

    lu: np.ndarray
    pivots: np.ndarray
    row_scale: np.ndarray
    column_scale: np.ndarray

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        """J x = rhs, as x = C S^-1 R rhs."""
        return self.column_scale * lapack.dgetrs(self.lu, self.pivots, self.row_scale * rhs)[0]

    @property
    def det_sign(self) -> float:
        """The sign of det J (R and C are positive)."""
        swaps = np.count_nonzero(self.pivots != np.arange(self.pivots.size))
        return float(np.prod(np.sign(np.diag(self.lu)))) * (-1.0) ** swaps


def _scale(magnitudes: np.ndarray) -> np.ndarray:
    """Reciprocal magnitudes, floored relative to the largest."""
    return 1.0 / np.maximum(magnitudes, EQUILIBRATION_FLOOR * max(float(magnitudes.max()), 1e-300))


def factorize(jac: np.ndarray, t: float, bound: float = SINGULAR_COND) -> Factor:
    """The factor of the equilibrated Jacobian; Singular if its condition estimate exceeds `bound`."""
    row_scale = _scale(np.abs(jac).max(axis=1))
    scaled = jac * row_scale[:, None]
    column_scale = _scale(np.abs(scaled).max(axis=0))
    scaled *= column_scale[None, :]
    lu, pivots, info = lapack.dgetrf(scaled)
    rcond = lapack.dgecon(lu, np.abs(scaled).sum(axis=0).max())[0] if info == 0 else 0.0
    if not rcond * bound > 1.0:
        cond = f"{1.0 / rcond:.3g}" if rcond > 0.0 else "infinite"
        raise Singular(f"constraint Jacobian is singular at t = {t:.6g} (condition {cond})", t)
    return Factor(lu, pivots, row_scale, column_scale)
