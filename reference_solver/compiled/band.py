"""LU with partial pivoting of a band matrix, its solves, and LAPACK's 1-norm condition estimate.

The store is flat, row i holding columns i - kl .. i + kl + ku at a[i * w + j - i + kl], w = 2 kl + ku + 1
(so entry (i, j) is at i (w - 1) + kl + j). As in LAPACK's dgbtrf, the multipliers of column j stay
where they were computed and each row interchange moves only the columns from j on; the solves
replay the interchanges in order. The factored diagonal holds 1 / U_jj, so solves multiply.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit


@njit(cache=True, error_model="numpy")
def norm1(a: np.ndarray, n: int, kl: int, ku: int, w: int, colsum: np.ndarray) -> float:
    """max_j sum_i |a_ij| of the (not yet factored) band matrix."""
    for j in range(n):
        colsum[j] = 0.0
    for i in range(n):
        for j in range(max(0, i - kl), min(n, i + ku + 1)):
            colsum[j] += abs(a[i * w + j - i + kl])
    worst = 0.0
    for j in range(n):
        worst = max(worst, colsum[j])
    return worst


@njit(cache=True, error_model="numpy")
def norm_inf(a: np.ndarray, n: int, kl: int, ku: int, w: int) -> float:
    """max_i sum_j |a_ij| of the (not yet factored) band matrix."""
    worst = 0.0
    for i in range(n):
        total = 0.0
        for j in range(max(0, i - kl), min(n, i + ku + 1)):
            total += abs(a[i * w + j - i + kl])
        worst = max(worst, total)
    return worst


@njit(cache=True, error_model="numpy")
def factor(a: np.ndarray, piv: np.ndarray, n: int, kl: int, ku: int, w: int) -> float:
    """Factor in place; returns the sign of the determinant, 0.0 if a pivot is zero or not finite."""
    sign, step = 1.0, w - 1
    for j in range(n):
        last, row_j = min(n, j + kl + 1), j * step + kl
        p, best = j, abs(a[row_j + j])
        for i in range(j + 1, last):
            v = abs(a[i * step + kl + j])
            if v > best:
                p, best = i, v
        piv[j] = p
        if best == 0.0 or not math.isfinite(best):
            return 0.0
        right = min(n, j + kl + ku + 1)
        if p != j:
            sign = -sign
            row_p = p * step + kl
            for c in range(j, right):
                a[row_j + c], a[row_p + c] = a[row_p + c], a[row_j + c]
        pivot = a[row_j + j]
        if pivot < 0.0:
            sign = -sign
        inverse = 1.0 / pivot
        a[row_j + j] = inverse
        for i in range(j + 1, last):
            row_i = i * step + kl
            multiplier = a[row_i + j] * inverse
            a[row_i + j] = multiplier
            if multiplier != 0.0:
                for c in range(j + 1, right):
                    a[row_i + c] -= multiplier * a[row_j + c]
    return sign


@njit(cache=True, error_model="numpy")
def solve(a: np.ndarray, piv: np.ndarray, n: int, kl: int, ku: int, w: int, b: np.ndarray) -> None:
    """b <- A^-1 b with the factors."""
    step = w - 1
    for j in range(n):
        p = piv[j]
        if p != j:
            b[j], b[p] = b[p], b[j]
        bj = b[j]
        if bj != 0.0:
            for i in range(j + 1, min(n, j + kl + 1)):
                b[i] -= a[i * step + kl + j] * bj
    for i in range(n - 1, -1, -1):
        row_i = i * step + kl
        s = b[i]
        for c in range(i + 1, min(n, i + kl + ku + 1)):
            s -= a[row_i + c] * b[c]
        b[i] = s * a[row_i + i]


@njit(cache=True, error_model="numpy")
def solve_transposed(a: np.ndarray, piv: np.ndarray, n: int, kl: int, ku: int, w: int, b: np.ndarray) -> None:
    """b <- A^-T b with the factors."""
    step = w - 1
    for i in range(n):
        s = b[i]
        for r in range(max(0, i - kl - ku), i):
            s -= a[r * step + kl + i] * b[r]
        b[i] = s * a[i * step + kl + i]
    for j in range(n - 1, -1, -1):
        s = b[j]
        for i in range(j + 1, min(n, j + kl + 1)):
            s -= a[i * step + kl + j] * b[i]
        b[j] = s
        p = piv[j]
        if p != j:
            b[j], b[p] = b[p], b[j]


@njit(cache=True, error_model="numpy")
def _signs(x: np.ndarray, signs: np.ndarray) -> bool:
    """signs <- sign(x) (+1 for x >= 0); True if no sign changed."""
    same = True
    for i in range(x.size):
        s = 1.0 if x[i] >= 0.0 else -1.0
        if s != signs[i]:
            same = False
        signs[i] = s
    return same


@njit(cache=True, error_model="numpy")
def _asum(x: np.ndarray) -> float:
    total = 0.0
    for i in range(x.size):
        total += abs(x[i])
    return total


@njit(cache=True, error_model="numpy")
def _argmax_abs(x: np.ndarray) -> int:
    best, k = -1.0, 0
    for i in range(x.size):
        if abs(x[i]) > best:
            best, k = abs(x[i]), i
    return k


@njit(cache=True, error_model="numpy", inline="always")
def _apply(a, piv, n, kl, ku, w, x, transposed):  # type: ignore[no-untyped-def]
    """x <- A^-1 x, or A^-T x if transposed."""
    if transposed:
        solve_transposed(a, piv, n, kl, ku, w, x)
    else:
        solve(a, piv, n, kl, ku, w, x)


@njit(cache=True, error_model="numpy")
def rcond(
    a: np.ndarray,
    piv: np.ndarray,
    n: int,
    kl: int,
    ku: int,
    w: int,
    anorm: float,
    x: np.ndarray,
    signs: np.ndarray,
    transposed: bool,
) -> float:
    """The reciprocal 1-norm condition number estimated as LAPACK's band routine dgbcon does
    (Higham's dlacn2 over the band LU with its row interchanges; dgecon, which ignores them, agrees
    except where the final alternating-sign vector decides); `transposed`: that of A^T, the
    infinity-norm one (then `anorm` is the infinity norm)."""
    if n == 0 or anorm == 0.0:
        return 0.0
    for i in range(n):
        x[i], signs[i] = 1.0 / n, 0.0
    _apply(a, piv, n, kl, ku, w, x, transposed)
    estimate = _asum(x)
    if n > 1:
        _signs(x, signs)
        for i in range(n):
            x[i] = signs[i]
        _apply(a, piv, n, kl, ku, w, x, not transposed)
        j = _argmax_abs(x)
        for iteration in range(2, 6):
            for i in range(n):
                x[i] = 0.0
            x[j] = 1.0
            _apply(a, piv, n, kl, ku, w, x, transposed)
            previous, estimate = estimate, _asum(x)
            if _signs(x, signs) or estimate <= previous:
                break
            for i in range(n):
                x[i] = signs[i]
            _apply(a, piv, n, kl, ku, w, x, not transposed)
            last, j = j, _argmax_abs(x)
            if x[last] == abs(x[j]) or iteration == 5:
                break
        for i in range(n):
            x[i] = (1.0 + i / (n - 1)) * (1.0 if i % 2 == 0 else -1.0)
        _apply(a, piv, n, kl, ku, w, x, transposed)
        estimate = max(estimate, 2.0 * _asum(x) / (3.0 * n))
    if estimate == 0.0 or not math.isfinite(estimate):
        return 0.0
    return (1.0 / estimate) / anorm
