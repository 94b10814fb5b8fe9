"""The compiled path's pieces on their own: band LU against dense algebra, the condition estimate against
the exact condition number and LAPACK's, the dense LU against LAPACK's, the spline kernel against the
profile, the band layout of a chain, and the guard of numba's cache."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from scipy.linalg import lu_factor
from scipy.linalg.lapack import dgecon

import scenarios
from reference_solver.compiled import band, dense_lu, path
from reference_solver.compiled.cache_guard import refresh
from reference_solver.compiled.evaluate import profile_points
from reference_solver.compiled.program import profile_tables
from reference_solver.compiled.structure import band_of
from scenarios import EccentricDisc, SplineProfile
from tests.support.band_store import band_store


def _banded(rng: np.random.Generator, n: int, kl: int, ku: int) -> np.ndarray:
    a = rng.standard_normal((n, n))
    rows, cols = np.indices((n, n))
    a[(cols - rows > ku) | (rows - cols > kl)] = 0.0
    return a


@pytest.mark.parametrize(
    ("n", "kl", "ku"),
    [(1, 0, 0), (2, 1, 1), (3, 1, 0), (9, 3, 4), (30, 4, 2), (40, 1, 7), (12, 11, 11), (8, 0, 2), (7, 2, 0)],
)
def test_band_lu_solves_like_dense_algebra(n: int, kl: int, ku: int) -> None:
    rng = np.random.default_rng(n + kl + ku)
    for scale in (1.0, 1e3, 1e-3, 10.0, 1.0):  # rcond does not depend on the scale; its iterates do
        a = scale * _banded(rng, n, kl, ku)
        store, piv, w = band_store(a, kl, ku), np.zeros(n, np.int64), 2 * kl + ku + 1
        anorm = band.norm1(store, n, kl, ku, w, np.zeros(n))
        assert anorm == pytest.approx(np.linalg.norm(a, 1)) and band.norm_inf(
            store, n, kl, ku, w
        ) == pytest.approx(np.linalg.norm(a, np.inf))
        sign = band.factor(store, piv, n, kl, ku, w)
        assert sign == np.sign(np.linalg.det(a))
        np.testing.assert_array_equal(piv, lu_factor(a)[1])  # LAPACK's partial pivoting: the same rows
        b = rng.standard_normal(n)
        x, y = b.copy(), b.copy()
        band.solve(store, piv, n, kl, ku, w, x)
        band.solve_transposed(store, piv, n, kl, ku, w, y)
        np.testing.assert_allclose(a @ x, b, atol=1e-10 * np.linalg.cond(a))
        np.testing.assert_allclose(a.T @ y, b, atol=1e-10 * np.linalg.cond(a))
        exact = 1.0 / (anorm * np.linalg.norm(np.linalg.inv(a), 1))
        estimate = band.rcond(store, piv, n, kl, ku, w, anorm, np.zeros(n), np.zeros(n), False)
        lapack = dgecon(lu_factor(a)[0], anorm, norm="1")[0]
        assert exact * (1 - 1e-9) <= estimate <= 10 * exact  # an estimate never undercuts the truth
        # the same estimator as LAPACK's dgecon on the same pivots: measured equal to 2.2e-15
        assert estimate == pytest.approx(lapack, rel=1e-13)
        anorm_inf = float(np.linalg.norm(a, np.inf))
        transposed = band.rcond(store, piv, n, kl, ku, w, anorm_inf, np.zeros(n), np.zeros(n), True)
        exact_inf = 1.0 / (anorm_inf * np.linalg.norm(np.linalg.inv(a), np.inf))
        assert exact_inf * (1 - 1e-9) <= transposed <= 10 * exact_inf
        assert transposed == pytest.approx(dgecon(lu_factor(a)[0], anorm_inf, norm="I")[0], rel=1e-13)


def test_condition_estimate_of_the_identity_and_of_no_norm() -> None:
    """The identity's rcond is exactly 1 (its 1-norm 1 too); as dgecon, 0 for a zero norm or no rows."""
    n, kl, ku = 4, 1, 1
    store, piv, w = band_store(np.eye(n), kl, ku), np.zeros(n, np.int64), 2 * kl + ku + 1
    assert band.factor(store, piv, n, kl, ku, w) == 1.0
    x, signs = np.zeros(n), np.zeros(n)
    for transposed in (False, True):
        assert band.rcond(store, piv, n, kl, ku, w, 1.0, x, signs, transposed) == 1.0
        assert band.rcond(store, piv, n, kl, ku, w, 0.0, x, signs, transposed) == 0.0
        assert band.rcond(store, piv, 0, kl, ku, w, 1.0, x, signs, transposed) == 0.0


def test_band_pivoting_keeps_the_first_of_equal_magnitudes_and_overflow_is_singular() -> None:
    """[[2, 1], [2, 3]]: |2| = |2|, row 0 stays (as LAPACK), the multiplier is exactly 1, det 4 > 0, and
    x = (1, 1) solves it for b = (3, 5). A regular matrix whose inverse overflows (entry -1e320 of
    [[1e-160, 1], [0, 1e-160]]^-1): its condition estimate is 0."""
    store, piv = band_store(np.array([[2.0, 1.0], [2.0, 3.0]]), 1, 1), np.zeros(2, np.int64)
    assert band.factor(store, piv, 2, 1, 1, 4) == 1.0
    np.testing.assert_array_equal(piv, [0, 1])
    b = np.array([3.0, 5.0])
    band.solve(store, piv, 2, 1, 1, 4, b)
    np.testing.assert_allclose(b, [1.0, 1.0], rtol=0, atol=1e-15)
    store = band_store(np.array([[1e-160, 1.0], [0.0, 1e-160]]), 1, 1)
    assert band.factor(store, piv, 2, 1, 1, 4) == 1.0
    with np.errstate(over="ignore", invalid="ignore"):
        assert band.rcond(store, piv, 2, 1, 1, 4, 1.0, np.zeros(2), np.zeros(2), False) == 0.0


def test_a_zero_pivot_reports_a_singular_matrix() -> None:
    a = np.array([[1.0, 2.0], [2.0, 4.0]])
    assert band.factor(band_store(a, 1, 1), np.zeros(2, np.int64), 2, 1, 1, 4) == 0.0


DENSE = {
    "random 5 x 5": np.random.default_rng(5).standard_normal((5, 5)),
    "multipliers of exactly 1 and -1/2": np.array([[2.0, 1.0, 1.0], [4.0, -6.0, 0.0], [-2.0, 7.0, 2.0]]),
    "a tie of magnitudes keeps the first row": np.array([[1.0, 2.0], [-1.0, 3.0]]),
    "a 1 x 1": np.array([[-4.0]]),
}


@pytest.mark.parametrize("name", DENSE)
def test_dense_lu_is_lapacks_and_solves(name: str) -> None:
    """The factors and pivots of LAPACK's getrf (scipy.linalg.lu_factor), solves to round-off."""
    a = DENSE[name]
    n = a.shape[0]
    store, piv = np.full((n + 1, n + 2), 3.0), np.zeros(n + 1, np.int64)  # only [:n, :n] is the matrix
    store[:n, :n] = a
    assert dense_lu.lu_factor(store, n, piv) is False
    lu, lapack_piv = lu_factor(a)
    np.testing.assert_allclose(store[:n, :n], lu, rtol=1e-14, atol=1e-15)
    np.testing.assert_array_equal(piv[:n], lapack_piv)
    assert np.all(store[n:] == 3.0) and np.all(store[:, n:] == 3.0)
    b = np.arange(1.0, n + 1.0) * (-1.0) ** np.arange(n)
    x, y = np.append(b, 7.0), np.append(b, 7.0)
    dense_lu.lu_solve(store, n, piv, x)
    dense_lu.lu_solve_transposed(store, n, piv, y)
    np.testing.assert_allclose(a @ x[:n], b, rtol=0, atol=1e-13)
    np.testing.assert_allclose(a.T @ y[:n], b, rtol=0, atol=1e-13)
    assert x[n] == 7.0 and y[n] == 7.0


def test_dense_lu_of_a_singular_matrix_flags_it_and_leaves_the_column_unscaled() -> None:
    """A zero first column: no pivot, the column left as it is and the rest still factored (as LAPACK)."""
    a = np.array([[0.0, 2.0, 1.0], [0.0, 4.0, 1.0], [0.0, 1.0, 3.0]])
    store, piv = a.copy(), np.zeros(3, np.int64)
    assert dense_lu.lu_factor(store, 3, piv)
    np.testing.assert_array_equal(piv, [0, 1, 2])
    # column 1 pivots on row 1 (4 > 1, row 0 done): multiplier 1/4, then 3 - 1/4; row 0 as it was
    np.testing.assert_allclose(
        store, [[0.0, 2.0, 1.0], [0.0, 4.0, 1.0], [0.0, 0.25, 2.75]], rtol=0, atol=1e-15
    )


def test_the_chain_keeps_a_constant_bandwidth() -> None:
    """What makes the cost linear in the number of loops: the band does not widen."""
    widths = set()
    for loops in (1, 10, 200):
        program = path.compiled(scenarios.build("four_bar_chain", overrides={"loops": loops})).program
        assert program is not None
        widths.add(tuple(program.sizes[2:4]))
    assert widths == {(4, 2)}


def test_band_layout_of_a_permuted_tridiagonal_pattern() -> None:
    n, rng = 50, np.random.default_rng(1)
    rows, cols = rng.permutation(n), rng.permutation(n)  # scrambled rows and columns
    entries = [(int(rows[i]), int(cols[j])) for i in range(n) for j in range(max(0, i - 1), min(n, i + 2))]
    layout = band_of(entries, n)
    assert layout.kl + layout.ku <= 4


PROFILES = [
    EccentricDisc(0.05, 0.01),
    SplineProfile.sample(EccentricDisc(0.05, 0.01), 12),
    SplineProfile(tuple(0.5 + 0.1 * math.sin(3 * k * 2 * math.pi / 9) for k in range(9))),
]


@pytest.mark.parametrize("profile", PROFILES, ids=["disc", "spline12", "spline9"])
def test_profile_kernel_reproduces_the_profile(profile) -> None:  # type: ignore[no-untyped-def]
    from scenarios.cam_profiles import profile_point

    table, splines = profile_tables([profile])
    knots = np.linspace(0.0, 2 * math.pi, 13)
    phis = np.concatenate([np.linspace(-7.0, 14.0, 211), knots, knots + 1e-15, [-1e-17, 2 * math.pi]])
    us = np.zeros((1, 4, 2))
    for phi in phis:
        profile_points(table, splines, np.array([float(phi)]), 0, us)
        np.testing.assert_allclose(us[0], profile_point(profile, float(phi)), rtol=1e-13, atol=1e-13)


def test_cache_guard_drops_machine_code_of_changed_sources(tmp_path: Path) -> None:
    (tmp_path / "kernel.py").write_text("x = 1\n")
    cache = tmp_path / "__pycache__"
    cache.mkdir()
    refresh(tmp_path)
    code = cache / "kernel.run-1.py311.nbi"
    code.write_text("machine code")
    refresh(tmp_path)
    assert code.exists()  # sources unchanged: kept
    (tmp_path / "kernel.py").write_text("x = 2\n")
    refresh(tmp_path)
    assert not code.exists()  # a source changed: dropped
