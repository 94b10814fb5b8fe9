"""rank_report on matrices whose singular values and null spaces are known by hand."""

from __future__ import annotations

import numpy as np
import pytest

from reference_solver.diagnostics import RANK_TOLERANCE, rank_report

LABELS = ["a", "b", "c"]


def test_a_repeated_row_is_one_lost_rank_naming_both_copies() -> None:
    """Rows a and c equal: the left null vector (1, 0, -1)/sqrt(2); b stays out."""
    m = np.array([[1.0, 2.0, 0.0], [0.0, 0.0, 3.0], [1.0, 2.0, 0.0]])
    report = rank_report(m, LABELS)
    assert (report.rank, report.deficiency, report.dependent_rows) == (2, 1, ("a", "c"))
    assert report.smallest < 1e-15


def test_a_regular_matrix_names_the_rows_of_its_weakest_direction() -> None:
    """diag(4, 2, 1e-3): full rank, smallest ratio 1e-3 / 4, the weakest direction is row c alone."""
    report = rank_report(np.diag([4.0, 2.0, 1e-3]), LABELS)
    assert (report.rank, report.deficiency, report.dependent_rows) == (3, 0, ("c",))
    assert report.smallest == pytest.approx(2.5e-4, rel=1e-14)


def test_the_tolerance_decides_what_counts_as_lost() -> None:
    """Singular value ratios 1, 0.5 and 1e-9: lost at the default 1e-8, kept at 1e-10."""
    m = np.diag([2.0, 1.0, 2e-9])
    assert RANK_TOLERANCE == 1e-8
    assert rank_report(m, LABELS).rank == 2
    assert rank_report(m, LABELS, tolerance=1e-10).rank == 3
    assert rank_report(m, LABELS, tolerance=0.6).rank == 1


def test_weights_of_exactly_one_tenth_and_below_are_not_named() -> None:
    """A null vector along (0.995, 0.1, 0): a is named, b (weight just under 0.1) is not."""
    u = np.array([0.995, 0.1, 0.0])
    u /= np.linalg.norm(u)
    m = np.eye(3) - np.outer(u, u)  # singular, left null vector u (weights 0.99499, 0.09999, 0)
    assert rank_report(m, LABELS).dependent_rows == ("a",)


def test_more_rows_than_columns_and_the_empty_and_zero_matrices() -> None:
    """3 x 2 of rank 2: deficiency 1 (rows minus rank), the null vector (1, 1, -1)/sqrt(3)."""
    m = np.array([[1.0, 0.0], [0.0, 1.0], [1.0, 1.0]])
    report = rank_report(m, LABELS)
    assert (report.rank, report.deficiency, report.dependent_rows) == (2, 1, ("a", "b", "c"))
    assert report.smallest == pytest.approx(1.0 / np.sqrt(3.0), rel=1e-14)  # sqrt(1) / sqrt(3)
    assert rank_report(np.zeros((0, 2)), []) == rank_report(np.zeros((0, 0)), [])
    empty = rank_report(np.zeros((0, 2)), [])
    assert (empty.rank, empty.deficiency, empty.dependent_rows, empty.smallest) == (0, 0, (), 1.0)
    zero = rank_report(np.zeros((2, 2)), LABELS[:2])
    assert (zero.rank, zero.deficiency, zero.smallest) == (0, 2, 0.0)


def test_one_row_a_tiny_matrix_and_no_columns() -> None:
    """One row (3, 4): rank 1, itself the weakest direction, ratio 1. A matrix of norm 1e-9 has rank 1
    relative to itself. No columns: every row lost, ratio 1 by convention."""
    assert rank_report(np.array([[3.0, 4.0]]), ["a"]) == rank_report(np.array([[4.0, 3.0]]), ["a"])
    one = rank_report(np.array([[3.0, 4.0]]), ["a"])
    assert (one.rank, one.deficiency, one.dependent_rows, one.smallest) == (1, 0, ("a",), 1.0)
    tiny = rank_report(np.diag([1e-9, 0.0]), LABELS[:2])
    assert (tiny.rank, tiny.deficiency, tiny.dependent_rows, tiny.smallest) == (1, 1, ("b",), 0.0)
    none = rank_report(np.zeros((2, 0)), LABELS[:2])
    assert (none.rank, none.deficiency, none.smallest) == (0, 2, 1.0)


def test_a_singular_value_exactly_at_the_tolerance_counts_as_lost() -> None:
    """diag(2, 1, 2e-8): the SVD of a diagonal matrix is exact, and 2e-8 is 1e-8 times 2 exactly."""
    assert rank_report(np.diag([2.0, 1.0, 2e-8]), LABELS).rank == 2
