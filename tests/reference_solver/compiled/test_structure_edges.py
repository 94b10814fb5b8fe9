"""The band structure's edge cases, each checked against what it must be by construction: a pattern
without entries, a scrambled bidiagonal pattern (a chain: the band must be bidiagonal again), the
parity of permutations with fixed points and cycles of every length, and the counts in the refusal."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from reference_solver.compiled.structure import StructurallySingular, _sign, band_of


def _parity_by_inversions(perm: list[int]) -> float:
    """The sign of a permutation from its number of inversions (an independent construction)."""
    inversions = sum(1 for i, j in itertools.combinations(range(len(perm)), 2) if perm[i] > perm[j])
    return -1.0 if inversions % 2 else 1.0


@pytest.mark.parametrize("n", [1, 2, 3, 4, 5])
def test_the_parity_of_every_permutation_is_that_of_its_inversions(n: int) -> None:
    for perm in itertools.permutations(range(n)):
        assert _sign(np.asarray(perm, dtype=np.int64)) == _parity_by_inversions(list(perm)), perm


def test_the_parity_of_the_empty_permutation_is_even() -> None:
    assert _sign(np.zeros(0, dtype=np.int64)) == 1.0


def test_a_pattern_without_entries_is_structurally_singular() -> None:
    with pytest.raises(StructurallySingular, match=r"^only 0 of 2 rows can be matched to columns$"):
        band_of([], 2)


@pytest.mark.parametrize("seed", [4, 5, 6])
def test_a_scrambled_chain_becomes_bidiagonal_again(seed: int) -> None:
    """A lower bidiagonal pattern (entries (i, i) and (i, i - 1): its only zero-free diagonal is the
    diagonal, and its graph is a path) with rows and columns shuffled: the matching and reverse
    Cuthill-McKee give back a band one entry wide beside the diagonal (kl + ku = 1), and each entry's
    position is its band slot."""
    n, rng = 15, np.random.default_rng(seed)
    rows, cols = rng.permutation(n), rng.permutation(n)
    entries = [(int(rows[i]), int(cols[j])) for i in range(n) for j in range(max(0, i - 1), i + 1)]
    layout = band_of(entries, n)
    assert layout.kl + layout.ku == 1 and layout.width == 2 * layout.kl + layout.ku + 1
    positions = set()
    for r, c in entries:
        i, j = int(layout.row_of[r]), int(layout.col_of[c])
        assert layout.row_perm[i] == r and layout.col_perm[j] == c
        assert -layout.kl <= j - i <= layout.ku
        assert layout.position(r, c) == i * layout.width + (j - i) + layout.kl
        positions.add(layout.position(r, c))
    assert len(positions) == len(entries) and max(positions) < n * layout.width


def test_the_refusal_counts_the_rows_that_can_be_matched() -> None:
    """Four rows on two columns' worth of entries (columns 2 and 3 empty): two can be matched."""
    with pytest.raises(StructurallySingular, match=r"^only 2 of 4 rows can be matched to columns$"):
        band_of([(0, 0), (1, 0), (2, 1), (3, 1), (0, 1)], 4)


def test_an_anti_diagonal_pattern_is_matched_with_an_odd_or_even_parity() -> None:
    """The anti-diagonal n x n pattern: its permutation matrix has determinant (-1)^(n(n-1)/2), and the
    band (one entry per row and column) is diagonal."""
    for n in (2, 3, 4, 5, 6):
        entries = [(i, n - 1 - i) for i in range(n)]
        layout = band_of(entries, n)
        assert (layout.kl, layout.ku) == (0, 0)
        expected = np.linalg.det(np.fliplr(np.eye(n)))
        assert layout.parity == round(expected), n
