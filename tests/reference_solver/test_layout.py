"""Where each unknown lives: three columns per body, then one per cam contact (worked by hand)."""

from __future__ import annotations

import numpy as np
import pytest

from reference_solver.layout import Layout

LAYOUT = Layout(("a", "b", "c"), ("k1", "k2"), 0.5)


def test_columns_of_bodies_and_contacts() -> None:
    assert LAYOUT.size == 11
    assert [LAYOUT.body_column(b) for b in ("a", "b", "c")] == [0, 3, 6]
    assert [LAYOUT.phi_column(k) for k in ("k1", "k2")] == [9, 10]


def test_column_scales_are_the_length_for_x_and_y_only() -> None:
    expected = [0.5, 0.5, 1.0] * 3 + [1.0, 1.0]
    np.testing.assert_array_equal(LAYOUT.column_scales(), expected)


def test_an_unknown_body_is_named() -> None:
    with pytest.raises(KeyError, match="unknown body 'z'"):
        LAYOUT.body_column("z")
