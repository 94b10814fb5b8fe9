"""LU with partial pivoting of a small dense matrix in place, and its solve, in numba: the
factorization LAPACK's dgetf2 makes (the row of largest magnitude pivots each column), written
out so that the dynamics kernel (compiled.rates) calls no LAPACK wrapper and allocates nothing."""

from __future__ import annotations

from numba import njit


@njit(cache=True, error_model="numpy")
def lu_factor(a, n, piv):  # type: ignore[no-untyped-def]
    """a[:n, :n] <- its LU factors (unit lower L below the diagonal), piv[k] the row swapped with
    row k; True if a pivot is exactly zero (that column is then left unscaled, as LAPACK does)."""
    singular = False
    for k in range(n):
        p, big = k, abs(a[k, k])
        for i in range(k + 1, n):
            if abs(a[i, k]) > big:
                p, big = i, abs(a[i, k])
        piv[k] = p
        if p != k:
            for j in range(n):
                a[k, j], a[p, j] = a[p, j], a[k, j]
        if a[k, k] == 0.0:
            singular = True
            continue
        inverse = 1.0 / a[k, k]
        for i in range(k + 1, n):
            a[i, k] *= inverse
        for i in range(k + 1, n):
            factor = a[i, k]
            if factor != 0.0:
                for j in range(k + 1, n):
                    a[i, j] -= factor * a[k, j]
    return singular


@njit(cache=True, error_model="numpy")
def lu_solve(a, n, piv, b):  # type: ignore[no-untyped-def]
    """b[:n] <- A^-1 b from lu_factor's a and piv."""
    for k in range(n):
        p = piv[k]
        if p != k:
            b[k], b[p] = b[p], b[k]
    for i in range(n):
        s = b[i]
        for j in range(i):
            s -= a[i, j] * b[j]
        b[i] = s
    for i in range(n - 1, -1, -1):
        s = b[i]
        for j in range(i + 1, n):
            s -= a[i, j] * b[j]
        b[i] = s / a[i, i]


@njit(cache=True, error_model="numpy")
def lu_solve_transposed(a, n, piv, b):  # type: ignore[no-untyped-def]
    """b[:n] <- A^-T b from lu_factor's a and piv (P A = L U, so A^T = U^T L^T P)."""
    for i in range(n):
        s = b[i]
        for j in range(i):
            s -= a[j, i] * b[j]
        b[i] = s / a[i, i]
    for i in range(n - 1, -1, -1):
        s = b[i]
        for j in range(i + 1, n):
            s -= a[j, i] * b[j]
        b[i] = s
    for k in range(n - 1, -1, -1):
        p = piv[k]
        if p != k:
            b[k], b[p] = b[p], b[k]
