"""Random row stores of C_q (ALI3-P's RowStore) with their dense equivalents and band widths."""

from __future__ import annotations

import numpy as np

from reference_solver.compiled.program import INT_COLUMNS, K_SLOT_COL, K_WIDTH, WIDTH


def random_row_store(rng: np.random.Generator, m: int, n: int, spread: int) -> tuple[np.ndarray, np.ndarray]:
    """A random row store: each row touches up to WIDTH slots within `spread` columns of a start,
    some slots unused (-1), a column sometimes twice in a row (the store sums them)."""
    ints = np.full((m, INT_COLUMNS), -7, np.int64)
    store = rng.standard_normal(m * WIDTH)
    for r in range(m):
        width = int(rng.integers(1, WIDTH + 1))
        start = int(rng.integers(0, n - spread))
        cols = rng.integers(start, start + spread + 1, size=width)
        cols[rng.random(width) < 0.2] = -1
        ints[r, K_WIDTH] = width
        ints[r, K_SLOT_COL : K_SLOT_COL + WIDTH] = -1
        ints[r, K_SLOT_COL : K_SLOT_COL + width] = cols
    return ints, store


def dense_jacobian(ints: np.ndarray, store: np.ndarray, m: int, n: int) -> np.ndarray:
    jac = np.zeros((m, n))
    for r in range(m):
        for k in range(ints[r, K_WIDTH]):
            col = ints[r, K_SLOT_COL + k]
            if col >= 0:
                jac[r, col] += store[r * WIDTH + k]
    return jac


def store_bandwidth(ints: np.ndarray, m: int) -> int:
    width = 0
    for r in range(m):
        cols = ints[r, K_SLOT_COL : K_SLOT_COL + ints[r, K_WIDTH]]
        cols = cols[cols >= 0]
        if cols.size:
            width = max(width, int(cols.max() - cols.min()))
    return width
