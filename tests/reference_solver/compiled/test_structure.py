"""The band structure of a sparse pattern: permutation parities against determinants, the band's
extent and store positions on scrambled patterns, and the refusal of a structurally singular one."""

from __future__ import annotations

import numpy as np
import pytest

from reference_solver.compiled import band
from reference_solver.compiled.structure import StructurallySingular, _sign, band_of


@pytest.mark.parametrize(
    "perm", [[0, 1, 2, 3], [1, 0, 2, 3], [1, 2, 0, 3], [1, 0, 3, 2], [3, 0, 1, 2], [2, 3, 1, 0, 4]]
)
def test_the_parity_of_a_permutation_is_the_determinant_of_its_matrix(perm: list[int]) -> None:
    p = np.asarray(perm, dtype=np.int64)
    assert _sign(p) == round(np.linalg.det(np.eye(p.size)[p]))


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_band_store_holds_the_matrix_permuted_with_its_parity(seed: int) -> None:
    """A scrambled pentadiagonal matrix with random values: every entry lies within the band at its
    position, the band matrix is the permuted one, and det(band) = parity det(A)."""
    n, rng = 12, np.random.default_rng(seed)
    rows, cols = rng.permutation(n), rng.permutation(n)
    a = np.zeros((n, n))
    for i in range(n):
        for j in range(max(0, i - 2), min(n, i + 3)):
            a[rows[i], cols[j]] = rng.uniform(0.5, 2.0) * rng.choice([-1.0, 1.0])
    entries = [(int(r), int(c)) for r, c in zip(*np.nonzero(a), strict=True)]
    layout = band_of(entries, n)
    assert layout.width == 2 * layout.kl + layout.ku + 1 and layout.kl + layout.ku <= 8
    np.testing.assert_array_equal(layout.row_perm[layout.row_of], np.arange(n))
    np.testing.assert_array_equal(layout.col_perm[layout.col_of], np.arange(n))
    permuted = a[np.ix_(layout.row_perm, layout.col_perm)]
    assert np.all(np.diag(permuted) != 0.0)  # the matching gives a zero-free diagonal
    at_row, at_col = np.nonzero(permuted)
    assert np.all(at_col - at_row <= layout.ku) and np.all(at_row - at_col <= layout.kl)
    store = np.zeros(n * layout.width)
    for r, c in entries:
        store[layout.position(r, c)] = a[r, c]
    assert np.count_nonzero(store) == len(entries)  # no two entries share a position
    piv, w = np.zeros(n, np.int64), layout.width
    x = np.arange(1.0, n + 1.0)
    sign = band.factor(store, piv, n, layout.kl, layout.ku, w)
    assert sign * layout.parity == np.sign(np.linalg.det(a))
    assert sign == np.sign(np.linalg.det(permuted))
    band.solve(store, piv, n, layout.kl, layout.ku, w, x)
    np.testing.assert_allclose(permuted @ x, np.arange(1.0, n + 1.0), rtol=0, atol=1e-10)


def test_a_pattern_with_an_empty_column_is_structurally_singular() -> None:
    with pytest.raises(StructurallySingular, match=r"^only 2 of 3 rows can be matched to columns$"):
        band_of([(0, 0), (1, 0), (2, 1), (0, 1)], 3)


def test_a_diagonal_pattern_has_no_band_beyond_it() -> None:
    layout = band_of([(2, 2), (0, 0), (1, 1)], 3)
    assert (layout.kl, layout.ku, layout.width, layout.parity) == (0, 0, 1, 1.0)
