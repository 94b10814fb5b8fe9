"""The instruction table's rows (compiled.program) against what they are defined to hold, worked by hand:
a row vector's four term places, which rows reuse the vectors of the row before, where each Jacobian
entry goes in a row-by-row and a dense store, a linear coefficient summed over a body named twice,
and the refusals of systems that have no table, matched whole."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from reference_solver.compiled.constraint_rows import (
    COMPONENT_X,
    POINT,
    ConstraintRowSpec,
    NotCompiled,
    Term,
)
from reference_solver.compiled.program import (
    K_REUSE,
    K_SLOT_COL,
    K_SLOT_POS,
    WIDTH,
    X_LINEAR,
    _padded,
    compile_dense,
    compile_program,
)
from reference_solver.system import ConstraintSystem
from scenarios import GROUND, AbsoluteDriver, Constant, GearPair, Point, Revolute
from scenarios.bodies import Body
from scenarios.scenario import Scenario
from tests.support.vocabulary import VOCABULARY


def _scenario(bodies: tuple[Body, ...], joints: tuple[Any, ...], drivers: tuple[Any, ...]) -> Scenario:
    return Scenario("by_hand", "default", bodies, joints, drivers, 1.0, 10, 1.0)


TERMS = tuple(Term(POINT, f"b{k}", (0.1 * k, 0.0)) for k in range(3))


def test_a_row_vector_has_two_term_places_and_no_more() -> None:
    """Vector A's terms fill places 0 and 1, B's places 2 and 3, None where a vector has fewer; a
    vector of three terms (on either side) has no place and is refused."""
    one, two = TERMS[:1], TERMS[:2]
    assert _padded(ConstraintRowSpec(COMPONENT_X, one, two)) == (one[0], None, *two)
    assert _padded(ConstraintRowSpec(COMPONENT_X, two, one)) == (*two, one[0], None)
    assert _padded(ConstraintRowSpec(COMPONENT_X)) == (None, None, None, None)
    for a, b in ((TERMS, one), (one, TERMS), (TERMS, ())):
        with pytest.raises(NotCompiled, match=r"^a row vector has more than two terms$"):
            _padded(ConstraintRowSpec(COMPONENT_X, a, b))


def test_a_row_reuses_the_vectors_of_the_row_before_exactly_when_its_constraint_repeats_them() -> None:
    """By constraint kind (constraint_rows.py): the y row of a revolute, a knife edge, a point path
    and a relative displacement takes the x row's vector; the ground pose's second and third rows
    have no vector, as the first; a prismatic's, roller's and flat face's two rows have different
    vectors; a constraint's first row never reuses (its vectors are another constraint's)."""
    expected = {
        "g": [0, 1, 1],
        "r0": [0, 1],
        "r": [0, 1],
        "p": [0, 0],
        "p0": [0, 0],
        "rr": [0],
        "gp": [0],
        "gp0": [0],
        "rp": [0],
        "k": [0, 1],
        "rc": [0, 0],
        "f": [0, 0],
        "ax": [0],
        "ay": [0],
        "at": [0],
        "rot": [0],
        "path": [0, 1],
        "disp": [0, 1],
    }
    system = ConstraintSystem(VOCABULARY)
    reuse = compile_dense(system).ints[:, K_REUSE]
    for eq, start in zip(system.equations, system.offsets, strict=False):
        assert list(reuse[start : start + eq.size]) == expected[eq.name], eq.name


def test_each_jacobian_entry_s_store_position_is_its_row_and_slot() -> None:
    """Row by row (ALI3-P's store) row r's local slot s is at r * WIDTH + s; dense (forward dynamics)
    entry (r, column) at r * n + column. Every slot with a position is one of the row's columns, and
    every entry the plain Jacobian has at a random state has a position."""
    system = ConstraintSystem(VOCABULARY)
    m, n = system.size, system.unknowns
    by_rows, dense = compile_dense(system, by_rows=True), compile_dense(system)
    np.testing.assert_array_equal(
        by_rows.ints[:, K_SLOT_COL : K_SLOT_COL + WIDTH], dense.ints[:, K_SLOT_COL : K_SLOT_COL + WIDTH]
    )
    jac = system.jacobian(np.random.default_rng(5).uniform(-1, 1, n), 0.3)
    placed = np.zeros((m, n), dtype=bool)
    for r in range(m):
        for s in range(WIDTH):
            col, row_pos, dense_pos = (
                int(by_rows.ints[r, K_SLOT_COL + s]),
                int(by_rows.ints[r, K_SLOT_POS + s]),
                int(dense.ints[r, K_SLOT_POS + s]),
            )
            assert (row_pos >= 0) == (dense_pos >= 0), (r, s)
            if row_pos >= 0:
                assert col >= 0, (r, s)
                assert row_pos == r * WIDTH + s, (r, s)
                assert dense_pos == r * n + col, (r, s)
                placed[r, col] = True
    assert not np.any((jac != 0.0) & ~placed)


def test_a_gear_fixed_on_its_carrier_sums_their_coefficients() -> None:
    """A gear pair whose second gear is the carrier itself (the plain equation sums the coefficients
    of a body named twice): r_i th_i + r_j th_c - (r_i + r_j) th_c = r_i (th_i - th_c), so the row's
    Jacobian is r_i on the gear's angle and -r_i on the carrier's, at any state."""
    ri, rj = 0.2, 0.5
    bodies = (Body("arm", (0.0, 0.0, 0.0)), Body("gear", (0.3, 0.0, 0.0)))
    joints = (
        Revolute("o", Point(GROUND, (0.0, 0.0)), Point("arm", (0.0, 0.0))),
        Revolute("a", Point("arm", (0.3, 0.0)), Point("gear", (0.0, 0.0))),
        GearPair("mesh", "gear", ri, "arm", rj, carrier="arm"),
    )
    system = ConstraintSystem(
        _scenario(bodies, joints, (AbsoluteDriver("d", "arm", "theta", Constant(0.1)),))
    )
    row = int(system.offsets[2])
    reals = compile_dense(system).reals[row, X_LINEAR : X_LINEAR + WIDTH]
    expected = np.zeros(WIDTH)
    expected[[2, 5]] = ri, -ri  # local slots: the gear's x, y, theta, then the arm's (the order named)
    np.testing.assert_allclose(reals, expected, rtol=0, atol=1e-15)
    plain = system.jacobian(np.random.default_rng(3).uniform(-1, 1, system.unknowns), 0.0)[row]
    np.testing.assert_allclose(plain, [0, 0, -ri, 0, 0, ri], rtol=0, atol=1e-15)  # arm's columns first


def test_systems_without_a_table_are_refused_whole() -> None:
    """No body and no constraint (0 for 0); a joint between two ground points and no body (2 rows for
    0 unknowns): neither compiler has anything to compile."""
    empty = _scenario((), (), ())
    grounded = _scenario((), (Revolute("gg", Point(GROUND, (0.0, 0.0)), Point(GROUND, (0.3, 0.4))),), ())
    for scenario, m in ((empty, 0), (grounded, 2)):
        system = ConstraintSystem(scenario)
        with pytest.raises(NotCompiled, match=rf"^{m} constraint rows for 0 unknowns: not a square system$"):
            compile_program(system)
        with pytest.raises(NotCompiled, match=rf"^{m} constraint rows for 0 unknowns: nothing to compile$"):
            compile_dense(system)


def test_a_square_system_with_an_unmatched_column_is_refused_with_the_count() -> None:
    """One body with x driven twice and y once: three rows for three unknowns, but no row touches
    the angle, so only two rows can be matched to columns (structurally singular)."""
    drivers = (
        AbsoluteDriver("x1", "b", "x", Constant(0.1)),
        AbsoluteDriver("x2", "b", "x", Constant(0.2)),
        AbsoluteDriver("y", "b", "y", Constant(0.3)),
    )
    system = ConstraintSystem(_scenario((Body("b", (0.0, 0.0, 0.0)),), (), drivers))
    with pytest.raises(NotCompiled, match=r"^only 2 of 3 rows can be matched to columns$"):
        compile_program(system)
