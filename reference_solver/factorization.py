"""LU factorization of the scaled Jacobian, with what the singularity checks need: the reciprocal
condition number and the determinant's sign, both nearly free once the factors exist."""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
from scipy.linalg import LinAlgWarning, lu_factor, lu_solve
from scipy.linalg.lapack import dgecon


@dataclass(frozen=True)
class Factorization:
    lu: np.ndarray
    pivots: np.ndarray
    rcond: float
    sign: float
    """The determinant's sign (+1, -1, or 0 when exactly singular)."""
    log_abs_determinant: float
    """log |det|: the determinant itself under- or overflows for large systems."""

    def relative_determinant(self, other: Factorization) -> tuple[float, float]:
        """This determinant and `other`'s, both divided by the larger magnitude (no overflow)."""
        top = max(self.log_abs_determinant, other.log_abs_determinant)
        return (
            self.sign * float(np.exp(self.log_abs_determinant - top)),
            other.sign * float(np.exp(other.log_abs_determinant - top)),
        )

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        return lu_solve((self.lu, self.pivots), rhs, check_finite=False)  # type: ignore[no-any-return]


def factorize(matrix: np.ndarray) -> Factorization:
    """Factor a square matrix; an exactly singular one gets rcond 0 instead of a warning."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", LinAlgWarning)
        lu, pivots = lu_factor(matrix, check_finite=False)
    anorm = float(np.linalg.norm(matrix, 1))
    rcond = float(dgecon(lu, anorm, norm="1")[0]) if anorm > 0 else 0.0
    diagonal = np.diag(lu)
    swaps = int(np.sum(pivots != np.arange(pivots.size)))
    sign = float(np.prod(np.sign(diagonal))) * (-1.0) ** swaps
    with np.errstate(divide="ignore"):
        log_abs = float(np.sum(np.log(np.abs(diagonal))))
    if not np.all(np.isfinite(diagonal)) or np.any(diagonal == 0.0):
        rcond = 0.0
    return Factorization(lu, pivots, rcond, sign, log_abs)
