"""The LU factors' by-products on matrices worked by hand: rcond, the determinant's sign and log."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from reference_solver.factorization import factorize


def test_a_diagonal_matrix() -> None:
    """diag(2, 3): det 6; 1-norm 3, its inverse's 1/2, so rcond = 1 / (3 / 2) = 2/3."""
    f = factorize(np.diag([2.0, 3.0]))
    assert f.sign == 1.0
    assert f.log_abs_determinant == pytest.approx(math.log(6.0), rel=1e-14)
    assert f.rcond == pytest.approx(2 / 3, rel=1e-12)
    np.testing.assert_allclose(f.solve(np.array([4.0, 9.0])), [2.0, 3.0], rtol=1e-15)


@pytest.mark.parametrize(
    ("matrix", "determinant"),
    [
        ([[0.0, 1.0], [1.0, 0.0]], -1.0),  # one row swap
        ([[1.0, 2.0], [3.0, 4.0]], -2.0),  # 4 - 6, pivoted on the 3
        ([[3.0, 4.0], [1.0, 2.0]], 2.0),  # 6 - 4, no swap
        ([[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]], -1.0),  # one swap of rows 1 and 3
        ([[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]], 1.0),  # a cycle: two swaps
        ([[-2.0, 0.0], [0.0, -5.0]], 10.0),  # two negative pivots
    ],
)
def test_the_determinants_sign_and_log(matrix: list[list[float]], determinant: float) -> None:
    f = factorize(np.array(matrix))
    assert f.sign == math.copysign(1.0, determinant)
    assert f.log_abs_determinant == pytest.approx(math.log(abs(determinant)), abs=1e-14)
    assert f.rcond > 0


@pytest.mark.parametrize(
    "matrix",
    [
        [[1.0, 2.0], [2.0, 4.0]],  # rank 1: the second pivot is exactly 0
        [[0.0, 0.0], [0.0, 0.0]],  # zero norm
        [[1.0, np.nan], [0.0, 1.0]],  # not finite
    ],
)
def test_an_exactly_singular_or_broken_matrix_has_rcond_zero(matrix: list[list[float]]) -> None:
    with np.errstate(all="ignore"):
        assert factorize(np.array(matrix)).rcond == 0.0


def test_a_full_matrix_rcond() -> None:
    """[[1, 2], [3, 4]]: 1-norm 6 (the second column), its inverse [[-2, 1], [1.5, -0.5]] has 1-norm
    3.5, so rcond = 1 / 21 (the 2-norm, 5.46, would give another number)."""
    assert factorize(np.array([[1.0, 2.0], [3.0, 4.0]])).rcond == pytest.approx(1 / 21, rel=1e-12)


def test_an_exactly_singular_matrix_has_determinant_sign_zero_without_a_warning() -> None:
    """[[1, 2], [2, 4]] pivots on the 2: the second pivot is 2 - (1/2) 4 = 0 exactly; log 0 is -inf,
    silently (factorize's own errstate)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        f = factorize(np.array([[1.0, 2.0], [2.0, 4.0]]))
    assert f.sign == 0.0 and f.log_abs_determinant == -math.inf


def test_relative_determinants() -> None:
    """det 6 and det -2, divided by the larger magnitude 6: 1 and -1/3, either way round."""
    six, minus_two = factorize(np.diag([2.0, 3.0])), factorize(np.array([[1.0, 2.0], [3.0, 4.0]]))
    assert six.relative_determinant(minus_two) == pytest.approx((1.0, -1 / 3), rel=1e-14)
    assert minus_two.relative_determinant(six) == pytest.approx((-1 / 3, 1.0), rel=1e-14)
