"""dynamics.passage's readings at their edges: a C_q with a zero row, readings that do not change (a
mechanism whose C_q is constant), and what a reading returns and keeps."""

from __future__ import annotations

import math

import numpy as np
import pytest

from reference_solver.dynamics.ali3p import PENALTY
from reference_solver.dynamics.passage import CAREFUL, FAR, NEAR, Watch, smallest_singular_value


def _dense_nonzero(jac: np.ndarray, mass: np.ndarray) -> np.ndarray:
    """The singular values of D^-1/2 C_q M^-1/2 over C_q's nonzero rows (a zero row adds a zero
    singular value and nothing else), by a dense SVD."""
    scaled = jac / np.sqrt(mass)
    norms = np.linalg.norm(scaled, axis=1)
    kept = scaled[norms > 0] / norms[norms > 0, None]
    return np.linalg.svd(kept, compute_uv=False)


@pytest.mark.parametrize("m", [4, 12])
def test_a_zero_row_of_c_q_counts_for_nothing(m: int) -> None:
    """A row of C_q that is zero (a constraint whose gradient vanishes there) has no inertia to scale
    by: it is left as it is (a zero row of the scaled matrix) and the rank it takes away is not
    counted, so with rank m - 1 the value is the smallest of the other rows' (dense SVD), on the
    dense path (4 rows of 6 columns, every row coupled) and on the banded one (12 rows, each
    coupling neighbouring columns)."""
    rng = np.random.default_rng(11)
    n = m + 2
    jac = np.zeros((m, n))
    for r in range(m):
        first = r if m > 4 else 0
        jac[r, first : first + 3] = rng.standard_normal(min(3, n - first))
    jac[m // 2] = 0.0
    mass = rng.uniform(0.5, 2.0, n)
    expected = _dense_nonzero(jac, mass)[-1]
    assert expected > 1e-3
    assert smallest_singular_value(jac, mass, m - 1) == pytest.approx(expected, rel=1e-9)


def test_readings_that_do_not_change_predict_nothing() -> None:
    """Two equal readings (C_q constant, as for a slider on a fixed line): s does not decrease, so
    no zero is predicted and the next reading is FAR steps on (a line through them would be flat:
    its zero, and the steps to the careful region, would divide by zero)."""
    watch = Watch(np.ones(3), 1)
    watch.readings = [(0.0, 0.5), (0.25, 0.5)]
    assert watch.zero() is None
    assert watch.steps_to_check(1e-3) == FAR
    below = math.sqrt(CAREFUL / PENALTY)
    watch.readings = [(0.0, below / 4), (0.25, below / 4)]  # flat inside the careful region
    assert watch.zero() is None and watch.careful and watch.steps_to_check(1e-3) == NEAR


def test_a_reading_returns_s_and_keeps_the_last_two() -> None:
    """read(t, C_q) returns s (smallest_singular_value at the watch's masses and rank, here a dense
    SVD of C_q's rows normalized, unit masses) and keeps the last two readings, the pair zero() fits
    its line through: three readings of C_q = [[1, 0], [1, eps]] for eps = 0.3, 0.2, 0.1."""
    mass = np.ones(2)
    watch = Watch(mass, 2)
    values = []
    for t, eps in [(0.0, 0.3), (0.1, 0.2), (0.2, 0.1)]:
        jac = np.array([[1.0, 0.0], [1.0, eps]])
        s = watch.read(t, jac)
        expected = np.linalg.svd(jac / np.linalg.norm(jac, axis=1)[:, None], compute_uv=False)[-1]
        assert s == pytest.approx(expected, rel=1e-12)
        values.append(s)
    assert watch.readings == [(0.1, values[1]), (0.2, values[2])]


def test_one_row_and_a_c_q_that_vanishes() -> None:
    """A single row, normalized, has the singular value 1 whatever it is; a C_q whose rows all vanish
    (every constraint's gradient zero there) has only zero singular values, so s = 0 at any rank the
    rows had elsewhere (not infinity, which means no rows or rank 0: nothing to watch)."""
    mass = np.array([1.0, 2.0, 0.5])
    assert smallest_singular_value(np.array([[3.0, 4.0, 1.0]]), mass, 1) == pytest.approx(1.0, rel=1e-14)
    assert smallest_singular_value(np.zeros((1, 3)), mass, 1) == 0.0
    assert smallest_singular_value(np.zeros((2, 3)), mass, 2) == 0.0
    assert smallest_singular_value(np.zeros((0, 3)), mass, 1) == math.inf
