"""A band matrix written into the compiled path's band store and read back out of it, for the band
kernels' and the constraint program's tests."""

from __future__ import annotations

import numpy as np


def band_store(a: np.ndarray, kl: int, ku: int) -> np.ndarray:
    """The band store of `a`; NaN in the slots of columns outside the matrix, which nothing may read."""
    n, w = a.shape[0], 2 * kl + ku + 1
    store = np.full(n * w, np.nan)
    for i in range(n):
        for j in range(max(0, i - kl), min(n, i + kl + ku + 1)):
            store[i * w + j - i + kl] = a[i, j]
    return store


def permuted_band(store: np.ndarray, perm: np.ndarray, n: int, kl: int, w: int) -> np.ndarray:
    """The n x n matrix a program's band `store` holds (kl subdiagonals, w slots a row), each entry
    put back at its unpermuted row perm[0, i] and column perm[1, j]; zero off the band."""
    read = np.zeros((n, n))
    for i in range(n):
        for slot in range(w):
            j = i - kl + slot
            if 0 <= j < n:
                read[perm[0, i], perm[1, j]] = store[i * w + slot]
    return read
