"""The band kernel's condition estimate (compiled.band.rcond) against truths of its own making: LAPACK's
band estimator dgbcon on dgbtrf's factors, the exact 1-norm of the inverse (numpy), and the
alternating vector's bound computed by a dense solve.

rcond is Higham's estimator (LAPACK's dlacn2) of ||A^-1||_1, applied to A^-1 through the band factors
with their row interchanges, as dgbcon does (dgecon applies U^-1 L^-1 without P, so its last step,
the alternating vector, sees the columns permuted and can differ from this one where that step
decides). Every value it returns is |A^-1 v|_1 / |v|_1 for some v, so 1 / (rcond ||A||) is a lower
bound of ||A^-1||_1; and its last step makes it at least 2 |A^-1 x|_1 / (3n), x_i = (-1)^i (1 +
i / (n - 1)), whose 1-norm is 3n/2. On about 1 random band in 250 that last step is the estimate,
so 1500 small random bands exercise it in both norms."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.linalg.lapack import dgbcon, dgbtrf

from reference_solver.compiled import band
from tests.support.band_store import band_store

MATRICES = 1500
AGREE = 1e-12
"""dgbcon against this kernel on the random bands below: measured 4.3e-13 at most (relative), the
two applying the same factors in another order (dgbcon scales its triangular solves, dlatbs)."""


def _lapack_band(a: np.ndarray, kl: int, ku: int) -> np.ndarray:
    """`a` in LAPACK's band store for dgbtrf: ab[kl + ku + i - j, j] = a[i, j], kl rows spare on top."""
    n = a.shape[0]
    ab = np.zeros((2 * kl + ku + 1, n))
    for i in range(n):
        for j in range(max(0, i - kl), min(n, i + ku + 1)):
            ab[kl + ku + i - j, j] = a[i, j]
    return ab


def _estimates(a: np.ndarray, kl: int, ku: int, transposed: bool) -> tuple[float, float, float]:
    """(this kernel's rcond, dgbcon's, ||A||) in the 1-norm, or the infinity norm if transposed."""
    n, w = a.shape[0], 2 * kl + ku + 1
    store, piv = band_store(a, kl, ku), np.zeros(n, np.int64)
    assert band.factor(store, piv, n, kl, ku, w) != 0.0
    anorm = float(np.linalg.norm(a, np.inf if transposed else 1))
    mine = band.rcond(store, piv, n, kl, ku, w, anorm, np.zeros(n), np.zeros(n), transposed)
    factors, lapack_piv, info = dgbtrf(_lapack_band(a, kl, ku), kl, ku)
    assert info == 0
    theirs, info = dgbcon(kl, ku, factors, lapack_piv, anorm, norm="I" if transposed else "1")
    assert info == 0
    return mine, float(theirs), anorm


def _alternating_bound(a: np.ndarray, transposed: bool) -> float:
    """2 |A^-1 x|_1 / (3n) for dlacn2's alternating x (of A^T if transposed), by a dense solve."""
    n = a.shape[0]
    x = (1.0 + np.arange(n) / (n - 1)) * np.where(np.arange(n) % 2 == 0, 1.0, -1.0)
    return 2.0 * float(np.abs(np.linalg.solve(a.T if transposed else a, x)).sum()) / (3.0 * n)


def _random_bands(seed: int):  # type: ignore[no-untyped-def]
    """Random bands of 3 to 8 rows with kl, ku >= 1 (so A^-1 has no structural zeros, whose
    computed signs, +-1e-16, would be a tie between the two codes' round-off)."""
    rng = np.random.default_rng(seed)
    for _ in range(MATRICES):
        n = int(rng.integers(3, 9))
        kl, ku = int(rng.integers(1, n)), int(rng.integers(1, n))
        a = rng.standard_normal((n, n))
        rows, cols = np.indices((n, n))
        a[(cols - rows > ku) | (rows - cols > kl)] = 0.0
        yield a, kl, ku


@pytest.mark.parametrize("transposed", [False, True], ids=["1-norm", "infinity norm"])
def test_the_estimate_is_dgbcon_s_also_where_the_alternating_vector_decides(transposed: bool) -> None:
    """On 1500 random bands: equal to dgbcon's; between the exact value and the alternating
    vector's bound; and on some of them (measured 6 of 1500 in each norm, seed 28) the estimate is
    that bound itself, which the iterations alone stay below."""
    decided = 0
    for a, kl, ku in _random_bands(28):
        mine, theirs, anorm = _estimates(a, kl, ku, transposed)
        assert mine == pytest.approx(theirs, rel=AGREE)
        exact = float(np.linalg.norm(np.linalg.inv(a.T if transposed else a), 1))
        bound = _alternating_bound(a, transposed)
        estimate = 1.0 / (mine * anorm)
        assert bound * (1 - 1e-12) <= estimate <= exact * (1 + 1e-12)
        decided += estimate == pytest.approx(bound, rel=1e-12)
    assert decided >= 3


@pytest.mark.parametrize("transposed", [False, True], ids=["1-norm", "infinity norm"])
def test_a_band_whose_estimate_grows_for_four_iterations(transposed: bool) -> None:
    """Bands found by a search (entries rounded to 2 digits) on which dlacn2 takes a new, larger
    column at each of its iterations 2 to 5: the estimate is the fifth column's, equal to dgbcon's
    and here to the exact norm (dense inverse)."""
    a = FOUR_STEPS[transposed]
    kl, ku = BANDS[transposed]
    mine, theirs, anorm = _estimates(a, kl, ku, transposed)
    exact = 1.0 / (anorm * np.linalg.norm(np.linalg.inv(a.T if transposed else a), 1))
    assert mine == pytest.approx(theirs, rel=1e-14) and mine == pytest.approx(exact, rel=1e-14)


FOUR_STEPS = {
    False: np.array(
        [
            [-0.06, -0.77, 1.97, 0.4, -0.63],
            [-0.55, 0.77, 0.83, -2.0, -1.51],
            [0.72, -0.13, -1.09, -0.93, -1.43],
            [-0.82, -1.77, -0.25, 0.02, -0.41],
            [1.57, -0.34, 0.56, -0.58, -1.07],
        ]
    ),
    True: np.array(
        [
            [1.54, -0.68, 0.65, 0.39, 0.59, 0.0, 0.0],
            [0.52, -1.06, -1.78, 0.38, -0.08, -1.06, 0.0],
            [0.0, 1.07, -0.82, 0.47, -0.63, -0.25, 0.39],
            [0.0, 0.0, -1.28, -0.93, -0.12, -1.3, 0.17],
            [0.0, 0.0, 0.0, 2.02, -1.12, 2.39, 0.19],
            [0.0, 0.0, 0.0, 0.0, -1.46, -0.18, -0.14],
            [0.0, 0.0, 0.0, 0.0, 0.0, 0.19, -1.75],
        ]
    ),
}
BANDS = {False: (4, 4), True: (1, 4)}


def test_a_diagonal_s_estimate_is_exact() -> None:
    """diag(d): the first column step takes the largest 1 / |d_i|, which is ||D^-1||_1 in both norms;
    rcond = min |d| / max |d| exactly (dyadic entries, so every step is exact)."""
    d = np.array([2.0, -0.25, 8.0, 0.5, -4.0])
    a = np.diag(d)
    for transposed in (False, True):
        for kl, ku in ((0, 0), (1, 1), (2, 1)):
            mine, theirs, _ = _estimates(a, kl, ku, transposed)
            assert mine == theirs == 0.25 / 8.0


@pytest.mark.parametrize("n", [2, 3, 6, 11])
def test_the_bidiagonal_of_ones_has_its_exact_condition_number(n: int) -> None:
    """A = I - (superdiagonal of ones): A^-1 is the upper triangle of ones, ||A^-1||_1 = n (its last
    column), ||A||_1 = 2, so rcond = 1 / (2n); ||A^-1||_inf = n too (its first row). The estimator
    finds that column at its second iteration: exact, and dgbcon's."""
    a = np.eye(n) - np.eye(n, k=1)
    assert np.array_equal(np.linalg.inv(a), np.triu(np.ones((n, n))))
    for transposed in (False, True):
        for kl, ku in ((0, 1), (1, 1), (1, 2)):
            mine, theirs, anorm = _estimates(a, kl, ku, transposed)
            assert anorm == 2.0 and mine == theirs == 1.0 / (2 * n)
