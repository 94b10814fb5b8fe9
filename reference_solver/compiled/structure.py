"""The band structure of a sparse square Jacobian, fixed once per scenario.

Rows are matched to columns for a zero-free diagonal (Hopcroft-Karp), then both are renumbered by
reverse Cuthill-McKee: a chain of loops becomes a matrix of small constant bandwidth, so that LU
with partial pivoting inside the band costs O(n). Row i of the band store holds columns
i - kl .. i + kl + ku (the extra kl for the fill of row interchanges), LAPACK dgbtrf's layout by rows.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


class StructurallySingular(ValueError):
    """No assignment of rows to columns exists: the Jacobian is singular whatever the values."""


@dataclass(frozen=True)
class Band:
    n: int
    kl: int
    ku: int
    row_perm: np.ndarray
    """Band row i holds original row row_perm[i]."""
    col_perm: np.ndarray
    """Band column j holds original column col_perm[j]."""
    row_of: np.ndarray
    """The inverse permutations: original row r is band row row_of[r]."""
    col_of: np.ndarray
    parity: float
    """The sign of both permutations together: det(band matrix) = parity * det(C_q)."""

    @property
    def width(self) -> int:
        return 2 * self.kl + self.ku + 1

    def position(self, row: int, col: int) -> int:
        """Index in the flat band store of the original entry (row, col)."""
        i, j = int(self.row_of[row]), int(self.col_of[col])
        return i * self.width + j - i + self.kl


def _sign(perm: np.ndarray) -> float:
    seen = np.zeros(perm.size, dtype=bool)
    sign = 1.0
    for start in range(perm.size):
        length = 0
        k = start
        while not seen[k]:
            seen[k] = True
            k = int(perm[k])
            length += 1
        if length and length % 2 == 0:
            sign = -sign
    return sign


def band_of(entries: list[tuple[int, int]], n: int) -> Band:
    """The band layout of the n x n pattern given by its (row, col) entries."""
    import scipy.sparse as sp  # on first use: only the compiled paths lay out a band
    from scipy.sparse.csgraph import maximum_bipartite_matching, reverse_cuthill_mckee

    rows, cols = zip(*entries, strict=True) if entries else ((), ())
    pattern = sp.csr_array((np.ones(len(rows)), (rows, cols)), shape=(n, n))
    match = maximum_bipartite_matching(pattern, perm_type="row")
    if np.any(match < 0):
        raise StructurallySingular(f"only {int(np.sum(match >= 0))} of {n} rows can be matched to columns")
    matched = pattern[match]
    symmetric = sp.csr_array(matched + matched.T)
    order = np.asarray(reverse_cuthill_mckee(symmetric, symmetric_mode=True), dtype=np.int64)
    row_perm, col_perm = np.asarray(match, dtype=np.int64)[order], order
    row_of, col_of = np.argsort(row_perm), np.argsort(col_perm)
    offsets = [int(col_of[c]) - int(row_of[r]) for r, c in entries]
    kl = max(0, -min(offsets, default=0))
    ku = max(0, max(offsets, default=0))
    return Band(n, kl, ku, row_perm, col_perm, row_of, col_of, _sign(row_perm) * _sign(col_perm))
