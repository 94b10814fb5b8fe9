"""Where ALI3-P's fixed steps meet a singular passage (C_q losing rank, as every rocker of A02 does
at each horizontal crossing): the smallest singular value s of C_q, scaled as the penalties are
(D^-1/2 C_q M^-1/2, D the rows' inertias, dynamics.ali3p.PENALTY), watched between steps and its
zero predicted by linear extrapolation (s is proportional to |t - t*| next to a simple passage,
so two readings give the instant).

Why: along the direction s measures the augmented Lagrangian contracts by 1/(1 + PENALTY s^2) per
iteration, so near a passage its small updates are taken for convergence while the rockers are
still off the crank; the exact (Schur complement) solution holds them to C's round-off over s,
which grows without bound as a step end nears the instant (a minimum-norm SVD projection of the
positions alone does the same, and leaves the rates). The grid (dynamics.ali3p_schedule)
therefore takes the steps where PENALTY s^2 < CAREFUL through the Schur complement from their
first iteration, and places three steps so that the predicted instant falls in the middle of one,
as an ODE solver locates an event: no step ends within END_VALUE / slope (at least half a step) of
it, so that the rockers stay on the crank wherever the instant falls in its step
(tests/reference_solver/dynamics/test_passage.py).
"""

from __future__ import annotations

import math

import numpy as np
from scipy import sparse
from scipy.linalg import eig_banded, eigvalsh

from reference_solver.dynamics.ali3p import PENALTY

CAREFUL = 4.0
"""Steps are careful where PENALTY s^2 is below this (s < 2e-4: about 60 steps of 2e-5 on either
side of an A02 passage)."""
FAR = 1000
"""Steps between readings of s while no passage is predicted."""
NEAR = 4
"""Steps between readings of s while the steps are careful."""
END_VALUE = 1.6e-6
"""The least s at either end of the step across a predicted instant (so at least END_VALUE / slope
from it, and never shorter than h): the ends fix the directions C_q is losing to C's round-off over
s, about 2e-17 / END_VALUE = 1.2e-11 rad on A02's rockers. Longer costs energy at outputs inside the
step (the quintic interpolant's error, O(length^2) there: on A02's first passage at h = 2e-5, 4.7e-9
of the kinetic energy for a step of h across it, 1.2e-8 for 2h, against 2.3e-9 at step ends)."""
FIRST = 50
"""Steps between the first two readings (a slope needs two)."""


def smallest_singular_value(jac: np.ndarray, mass: np.ndarray, rank: int) -> float:
    """The rank-th singular value of D^-1/2 C_q M^-1/2 (D the diagonal of C_q M^-1 C_q^T): the
    smallest the rows' structural rank keeps (redundant rows give zeros at every configuration).
    From the banded eigenvalue problem of its Gram matrix where C_q's rows make it banded."""
    scaled = jac / np.sqrt(mass)[None, :]
    norms = np.sqrt(np.einsum("ij,ij->i", scaled, scaled))
    scaled = scaled / np.where(norms > 0, norms, 1.0)[:, None]
    m = scaled.shape[0]
    if rank == 0 or m == 0:
        return math.inf
    gram = sparse.csr_matrix(scaled)
    gram = (gram @ gram.T).tocoo()
    width = int(np.max(np.abs(gram.row - gram.col), initial=0))
    index = m - rank
    if width > m // 4:
        value = float(eigvalsh(gram.toarray(), subset_by_index=(index, index))[0])
    else:
        band = np.zeros((width + 1, m))
        upper = gram.col >= gram.row
        band[width + gram.row[upper] - gram.col[upper], gram.col[upper]] = gram.data[upper]
        value = float(eig_banded(band, eigvals_only=True, select="i", select_range=(index, index))[0])
    return math.sqrt(max(value, 0.0))


class Watch:
    """Readings of s at times, and what they predict: whether the steps are careful and when s
    reaches zero."""

    def __init__(self, mass: np.ndarray, rank: int) -> None:
        self.mass, self.rank = mass, rank
        self.readings: list[tuple[float, float]] = []
        self.careful_below = math.sqrt(CAREFUL / PENALTY)

    def read(self, t: float, jac: np.ndarray) -> float:
        s = smallest_singular_value(jac, self.mass, self.rank)
        self.readings = [*self.readings[-1:], (t, s)]
        return s

    def forget(self) -> None:
        """Drop the readings (after a passage: a slope across the instant means nothing)."""
        self.readings = []

    @property
    def careful(self) -> bool:
        return bool(self.readings) and self.readings[-1][1] < self.careful_below

    def zero(self) -> tuple[float, float] | None:
        """The time s reaches zero on the line through the last two readings, and the line's
        slope (its decrease per second), if it decreases."""
        if len(self.readings) < 2:
            return None
        (t1, s1), (t2, s2) = self.readings
        if not s2 < s1:
            return None
        slope = (s1 - s2) / (t2 - t1)
        return t2 + s2 / slope, slope

    def steps_to_check(self, h: float) -> int:
        """Steps to the next reading: NEAR while careful, FIRST after a first reading, else half
        the predicted time to the careful region (at least NEAR, at most FAR)."""
        if self.careful:
            return NEAR
        if len(self.readings) < 2:
            return FIRST
        (t1, s1), (t2, s2) = self.readings
        if not s2 < s1:
            return FAR
        ahead = (s2 - self.careful_below) * (t2 - t1) / (s1 - s2) / h
        return int(min(FAR, max(NEAR, ahead / 2)))
