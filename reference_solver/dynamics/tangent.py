"""ALI3-P's iteration matrix W = P + h^2/4 C_q^T diag(alpha) C_q, assembled and factored once per
step. Its pattern is the constraints' (each row touches its equation's columns): a mechanism whose
bodies are listed along its chains (the N-four-bar) gives a banded W, factored by LAPACK's banded
LU in O(n b^2) instead of O(n^3); otherwise, or with force elements (whose K and D may couple any
bodies), W is dense.
"""

from __future__ import annotations

import numpy as np
from scipy.linalg import lapack, lu_factor, lu_solve

from reference_solver.system import ConstraintSystem

BANDED_FROM = 40
"""Systems of at least this many coordinates, whose W is banded with a half-bandwidth of at most a
quarter of the size, take the banded factorization."""


class Tangent:
    """Assembles and factors W; `solve` applies W^-1."""

    def __init__(self, system: ConstraintSystem, dense_weight: bool) -> None:
        rows, first, second = [], [], []
        for eq, start in zip(system.equations, system.offsets, strict=False):
            columns = np.asarray(eq.columns, dtype=int)
            a, b = np.meshgrid(columns, columns, indexing="ij")
            for k in range(eq.size):
                rows.append(np.full(a.size, start + k))
                first.append(a.ravel())
                second.append(b.ravel())
        self.n = system.unknowns
        self.rows = np.concatenate(rows) if rows else np.zeros(0, dtype=int)
        self.first = np.concatenate(first) if first else np.zeros(0, dtype=int)
        self.second = np.concatenate(second) if second else np.zeros(0, dtype=int)
        width = int(np.max(np.abs(self.first - self.second), initial=0))
        self.banded = not dense_weight and self.n >= BANDED_FROM and 4 * width <= self.n
        self.width = width
        self.factors: tuple[np.ndarray, np.ndarray] | None = None

    def factor(self, weight: np.ndarray, jac: np.ndarray, alpha: np.ndarray, factor: float) -> None:
        """Factor W = weight + factor * C_q^T diag(alpha) C_q (`weight` the diagonal of M in the
        banded case, a dense matrix otherwise)."""
        if not self.banded:
            self.factors = lu_factor(weight + factor * (jac.T @ (alpha[:, None] * jac)), check_finite=False)
            return
        n, w = self.n, self.width
        values = factor * alpha[self.rows] * jac[self.rows, self.first] * jac[self.rows, self.second]
        # LAPACK band storage for gbtrf: W[i, j] at ab[2w + i - j, j] (w extra rows for the fill-in)
        flat = (2 * w + self.first - self.second) * n + self.second
        # bincount of no weights (a system without constraint rows) counts in integers: float it
        ab = np.bincount(flat, weights=values, minlength=(3 * w + 1) * n).astype(float).reshape(3 * w + 1, n)
        ab[2 * w] += weight
        lu, pivots, info = lapack.dgbtrf(ab, w, w)
        if info != 0:
            raise np.linalg.LinAlgError(f"ALI3-P's iteration matrix is singular (LAPACK dgbtrf info {info})")
        self.factors = (lu, pivots)

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        assert self.factors is not None
        if not self.banded:
            return lu_solve(self.factors, rhs, check_finite=False)  # type: ignore[no-any-return]
        lu, pivots = self.factors
        x, _ = lapack.dgbtrs(lu, self.width, self.width, rhs, pivots)
        return x  # type: ignore[no-any-return]
