"""ALI3-P's iteration matrix (compiled.ali3p_matrix) against dense linear algebra on random row stores:
the products with C_q and C_q^T against the dense C_q built from the store, the banded Cholesky
factor of W = M + weight C_q^T diag(alpha) C_q against numpy's Cholesky of the dense W, and the
banded solve against numpy's solve. Small sizes, so the kernels stay fast uncompiled (mutation)."""

from __future__ import annotations

import numpy as np
import pytest

from reference_solver.compiled.ali3p_matrix import factor, jac_t_times, jac_times, solve
from reference_solver.compiled.program import INT_COLUMNS, K_SLOT_COL, K_WIDTH, WIDTH
from tests.support.row_stores import dense_jacobian, random_row_store, store_bandwidth


def _to_band(lower: np.ndarray, w: int) -> np.ndarray:
    n = len(lower)
    band = np.zeros((n, w + 1))
    for i in range(n):
        for k in range(min(i, w) + 1):
            band[i, k] = lower[i, i - k]
    return band


CASES = [(12, 7, 3, 0), (15, 12, 5, 1), (9, 4, 8, 2), (20, 30, 2, 3)]
"""(n, m, spread, seed): fewer and more rows than columns, bands narrow and full."""


@pytest.mark.parametrize(("n", "m", "spread", "seed"), CASES)
def test_products_with_the_jacobian_are_the_dense_products(n: int, m: int, spread: int, seed: int) -> None:
    rng = np.random.default_rng(seed)
    spread = min(spread, n - 1)
    ints, store = random_row_store(rng, m, n, spread)
    jac = dense_jacobian(ints, store, m, n)
    x, y = rng.standard_normal(n), rng.standard_normal(m)
    out = np.full(m + 3, 99.0)
    jac_times(ints, store, m, x, out)
    np.testing.assert_allclose(out[:m], jac @ x, rtol=1e-13, atol=1e-13)
    assert np.all(out[m:] == 99.0)
    out_t = np.full(n + 3, 99.0)
    jac_t_times(ints, store, m, n, y, out_t)
    np.testing.assert_allclose(out_t[:n], jac.T @ y, rtol=1e-13, atol=1e-13)
    assert np.all(out_t[n:] == 99.0)


@pytest.mark.parametrize(("n", "m", "spread", "seed"), CASES)
@pytest.mark.parametrize("extra", [0, 2])
def test_factor_is_the_cholesky_factor_of_w_and_solve_inverts_it(
    n: int, m: int, spread: int, seed: int, extra: int
) -> None:
    rng = np.random.default_rng(seed)
    spread = min(spread, n - 1)
    ints, store = random_row_store(rng, m, n, spread)
    jac = dense_jacobian(ints, store, m, n)
    mass = rng.uniform(0.5, 2.0, n)
    alpha = rng.uniform(0.5, 3.0, m)
    weight = 0.37
    w_dense = np.diag(mass) + weight * jac.T @ (alpha[:, None] * jac)
    w = min(store_bandwidth(ints, m) + extra, n - 1)
    band = rng.standard_normal((n, w + 1))  # garbage: factor must overwrite every entry
    assert factor(ints, store, mass, alpha, n, m, w, band, weight)
    np.testing.assert_allclose(band, _to_band(np.linalg.cholesky(w_dense), w), rtol=1e-12, atol=1e-12)
    b = rng.standard_normal(n)
    x = b.copy()
    solve(band, n, w, x)
    np.testing.assert_allclose(w_dense @ x, b, rtol=1e-11, atol=1e-11 * float(np.linalg.norm(w_dense, 1)))


@pytest.mark.parametrize(("n", "w", "seed"), [(1, 0, 0), (6, 1, 1), (10, 3, 2), (7, 6, 3)])
def test_solve_is_the_two_triangular_solves_of_a_given_factor(n: int, w: int, seed: int) -> None:
    """solve alone, on a banded factor made by hand (not by factor)."""
    rng = np.random.default_rng(seed)
    lower = np.tril(rng.standard_normal((n, n))) * (np.subtract.outer(np.arange(n), np.arange(n)) <= w)
    lower[np.diag_indices(n)] = rng.uniform(1.0, 2.0, n)
    b = rng.standard_normal(n + 2)
    x = b.copy()
    solve(_to_band(lower, w), n, w, x)
    np.testing.assert_allclose(lower @ lower.T @ x[:n], b[:n], rtol=1e-12, atol=1e-12)
    assert np.all(x[n:] == b[n:])


def test_factor_refuses_a_w_that_is_not_positive_definite() -> None:
    """A column with zero mass that no row touches makes W singular (pivot exactly 0), a negative
    mass makes it indefinite: both are refused, not factored."""
    rng = np.random.default_rng(5)
    n, m = 6, 3
    ints = np.full((m, INT_COLUMNS), -1, np.int64)
    ints[:, K_WIDTH] = 2
    ints[:, K_SLOT_COL : K_SLOT_COL + 2] = [[0, 1], [1, 2], [2, 3]]
    store = rng.standard_normal(m * WIDTH)
    alpha = np.ones(m)
    for bad in (0.0, -1.0):
        mass = np.ones(n)
        mass[5] = bad
        assert not factor(ints, store, mass, alpha, n, m, 1, np.zeros((n, 2)), 0.5)
    mass = np.ones(n)
    mass[4] = 0.0  # untouched by any row, zero mass: singular
    assert not factor(ints, store, mass, alpha, n, m, 1, np.zeros((n, 2)), 0.5)
    mass = np.ones(n)
    mass[1] = 0.0  # zero mass, but rows 0 and 1 give it stiffness: positive definite
    assert factor(ints, store, mass, alpha, n, m, 1, np.zeros((n, 2)), 0.5)
