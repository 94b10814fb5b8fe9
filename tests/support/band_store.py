"""A band matrix written into the compiled path's band store, for the band kernels' tests."""

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
