"""ALI3-P's iteration matrix in numba: products with C_q stored row by row (program.RowStore) and
W = M + weight C_q^T diag(alpha) C_q factored by a banded Cholesky (M diagonal: no force elements),
for compiled.ali3p_kernel."""

from __future__ import annotations

import math

from numba import njit

from reference_solver.compiled.program import K_SLOT_COL, K_WIDTH, WIDTH


@njit(cache=True, error_model="numpy", inline="always")
def jac_times(ints, store, m, x, out):  # type: ignore[no-untyped-def]
    """out[:m] <- C_q x."""
    for r in range(m):
        s = 0.0
        for k in range(ints[r, K_WIDTH]):
            col = ints[r, K_SLOT_COL + k]
            if col >= 0:
                s += store[r * WIDTH + k] * x[col]
        out[r] = s


@njit(cache=True, error_model="numpy", inline="always")
def jac_t_times(ints, store, m, n, y, out):  # type: ignore[no-untyped-def]
    """out[:n] <- C_q^T y."""
    for i in range(n):
        out[i] = 0.0
    for r in range(m):
        for k in range(ints[r, K_WIDTH]):
            col = ints[r, K_SLOT_COL + k]
            if col >= 0:
                out[col] += store[r * WIDTH + k] * y[r]


@njit(cache=True, error_model="numpy")
def factor(ints, store, mass, alpha, n, m, w, band, weight):  # type: ignore[no-untyped-def]
    """band <- the Cholesky factor L of W = M + weight C_q^T diag(alpha) C_q (L[i, j] at band[i, i - j],
    w its half-bandwidth); False if W is not numerically positive definite."""
    for i in range(n):
        band[i, 0] = mass[i]
        for k in range(1, w + 1):
            band[i, k] = 0.0
    for r in range(m):
        for a in range(ints[r, K_WIDTH]):
            ca = ints[r, K_SLOT_COL + a]
            if ca < 0:
                continue
            va = weight * alpha[r] * store[r * WIDTH + a]
            for b in range(ints[r, K_WIDTH]):
                cb = ints[r, K_SLOT_COL + b]
                if 0 <= cb <= ca:
                    band[ca, ca - cb] += va * store[r * WIDTH + b]
    for j in range(n):
        s = band[j, 0]
        for k in range(1, min(j, w) + 1):
            s -= band[j, k] * band[j, k]
        if not s > 0.0:
            return False
        d = math.sqrt(s)
        band[j, 0] = d
        for i in range(j + 1, min(n, j + w + 1)):
            s = band[i, i - j]
            for p in range(max(0, i - w), j):
                s -= band[i, i - p] * band[j, j - p]
            band[i, i - j] = s / d
    return True


@njit(cache=True, error_model="numpy")
def solve(band, n, w, b):  # type: ignore[no-untyped-def]
    """b[:n] <- W^-1 b from factor's L (L y = b, then L^T x = y)."""
    for i in range(n):
        s = b[i]
        for p in range(max(0, i - w), i):
            s -= band[i, i - p] * b[p]
        b[i] = s / band[i, 0]
    for i in range(n - 1, -1, -1):
        s = b[i]
        for p in range(i + 1, min(n, i + w + 1)):
            s -= band[p, p - i] * b[p]
        b[i] = s / band[i, 0]
