"""Rank and dependency diagnostics of a constraint Jacobian, from its singular value decomposition."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

RANK_TOLERANCE = 1e-8
"""Singular values below this fraction of the largest count as lost (on the scaled Jacobian)."""


@dataclass(frozen=True)
class RankReport:
    rank: int
    deficiency: int
    dependent_rows: tuple[str, ...]
    smallest: float
    """The smallest singular value divided by the largest."""


def rank_report(
    scaled_jacobian: np.ndarray, labels: list[str], tolerance: float = RANK_TOLERANCE
) -> RankReport:
    """The numerical rank of a (scaled) Jacobian and the rows that combine into its null space.

    A row is named dependent when it carries a significant weight in a left singular vector of a
    lost singular value (or of the smallest one, if none is lost): those rows are linearly dependent
    on each other, or nearly so.
    """
    rows, cols = scaled_jacobian.shape
    if rows == 0:
        return RankReport(0, 0, (), 1.0)
    u, s, _ = np.linalg.svd(scaled_jacobian)
    top = s[0] if s.size and s[0] > 0 else 1.0
    rank = int(np.sum(s > tolerance * top))
    deficiency = rows - rank
    # With no lost value (a configuration near, not at, a singularity), name the rows of the weakest.
    lost = u[:, rank:] if rank < rows else u[:, min(rows, cols) - 1 :]
    weights = np.max(np.abs(lost), axis=1) if lost.size else np.zeros(rows)
    dependent = tuple(labels[k] for k in np.flatnonzero(weights > 0.1))
    smallest = float(s[min(rows, cols) - 1] / top) if min(rows, cols) else 1.0
    return RankReport(rank, deficiency, dependent, smallest)
