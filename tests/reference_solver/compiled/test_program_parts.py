"""The instruction table's parts against independent constructions: the profile tables of several cam
profiles in one program against each profile's own radii, the band store of a band without
subdiagonal against the plain scaled Jacobian, C_q stored row by row (ALI3-P's RowStore)
against the plain path's dense Jacobian, and the refusals whole."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import scenarios
from reference_solver.compiled.constraint_rows import NotCompiled
from reference_solver.compiled.evaluate import evaluate, profile_points, radii
from reference_solver.compiled.program import (
    DISC,
    K_SLOT_COL,
    LOBED,
    S_KL,
    S_WIDTH,
    SPLINE,
    WIDTH,
    compile_dense,
    compile_program,
    profile_tables,
)
from reference_solver.system import ConstraintSystem
from scenarios import AbsoluteDriver, Constant
from scenarios.cam_profiles import EccentricDisc, LobedProfile, SplineProfile
from tests.support.band_store import permuted_band
from tests.support.hand_crank import crank_scenario
from tests.support.vocabulary import NAMES, VOCABULARY

SPLINE_A = SplineProfile.sample(EccentricDisc(0.05, 0.01), 12)
SPLINE_B = SplineProfile.sample(EccentricDisc(0.08, 0.03), 7)
PROFILES = [SPLINE_A, EccentricDisc(0.04, 0.015), SPLINE_B, SPLINE_A, LobedProfile(0.05, 0.01, 3)]
ANGLES = (0.0, 0.3, 1.0, 2.5, math.pi, 4.0, 6.0, 2.0 * math.pi - 1e-9, 7.5, -0.4, -9.0)


def test_every_contact_s_table_gives_its_own_profile_s_radii() -> None:
    """Two splines of 12 and 7 intervals, one of them on two contacts, a disc and a lobed profile in
    one program: the kernel's d, d', d'', d''' of each contact are its profile's own (the spline's at
    every interval, through phi beyond one turn and below 0)."""
    table, splines = profile_tables(PROFILES)
    assert [int(k) for k in table[:, 0]] == [SPLINE, DISC, SPLINE, SPLINE, LOBED]
    assert splines.shape == (12 + 1 + 7 + 1, 5)  # each spline once, with its closing knot
    for contact, profile in enumerate(PROFILES):
        for phi in ANGLES:
            mine = radii(table, splines, contact, phi)
            np.testing.assert_allclose(
                mine, profile.radii(phi), rtol=0, atol=1e-12, err_msg=f"{contact} {phi}"
            )


def test_a_spline_s_rows_are_its_knots_and_local_cubics() -> None:
    """The knots at equal steps 2 pi / 7 from 0 to 2 pi (the last one closing the turn) and, per
    interval, the scipy spline's value and derivatives at its left knot: d, d', d''/2, d'''/6."""
    table, splines = profile_tables([SPLINE_B])
    np.testing.assert_allclose(splines[:, 0], 2.0 * math.pi * np.arange(8) / 7, rtol=0, atol=1e-15)
    spline = SPLINE_B.spline
    for k in range(7):
        knot = 2.0 * math.pi * k / 7
        expected = [spline(knot, d) / math.factorial(d) for d in range(4)]
        np.testing.assert_allclose(splines[k, 1:], expected, rtol=0, atol=1e-12)
    assert list(table[0]) == [SPLINE, 0, 7, 0.0, 0.0]


def test_an_unknown_profile_is_named() -> None:
    with pytest.raises(NotCompiled, match=r"^no compiled kernel for profile str$"):
        profile_tables(["a disc"])  # type: ignore[list-item]


def test_c_q_stored_row_by_row_is_the_plain_jacobian() -> None:
    """compile_dense(by_rows=True), ALI3-P's store: row r's entry at its local slot s (column
    ints[r, K_SLOT_COL + s]) at r * WIDTH + s. Read back into a dense matrix it is the plain path's C_q
    (unscaled) on every constraint kind, and the slots the kernel leaves alone are zero there."""
    system = ConstraintSystem(VOCABULARY)
    p = compile_dense(system, by_rows=True)
    m, n, contacts = system.size, system.unknowns, p.profiles.shape[0]
    rng = np.random.default_rng(17)
    for _ in range(4):
        q, qd, t = rng.uniform(-1, 1, n), rng.normal(size=n), float(rng.uniform(0, 2))
        store, us = np.full(m * WIDTH, np.nan), np.empty((contacts, 4, 2))
        profile_points(p.profiles, p.splines, q, (n - contacts) // 3, us)
        work, jac = np.empty((5, max(len(NAMES), WIDTH))), np.empty((2, 2, WIDTH))
        evaluate(p.ints, p.reals, q, qd, t, np.empty(m), np.empty(m), store, work, jac, us)
        read = np.zeros((m, n))
        for r in range(m):
            for s in range(WIDTH):
                col = int(p.ints[r, K_SLOT_COL + s])
                if col >= 0 and not np.isnan(store[r * WIDTH + s]):
                    read[r, col] = store[r * WIDTH + s]
        expected = system.jacobian(q, t)
        np.testing.assert_allclose(read, expected, rtol=0, atol=1e-12 * np.max(np.abs(expected)))


def test_a_system_that_is_not_square_or_empty_is_refused_whole() -> None:
    four_bar = scenarios.build("four_bar")
    under = ConstraintSystem(dataclasses.replace(four_bar, drivers=()))
    with pytest.raises(NotCompiled, match=r"^8 constraint rows for 9 unknowns: not a square system$"):
        compile_program(under)
    free = ConstraintSystem(dataclasses.replace(four_bar, joints=(), drivers=()))
    with pytest.raises(NotCompiled, match=r"^0 constraint rows for 9 unknowns: nothing to compile$"):
        compile_dense(free)
    with pytest.raises(NotCompiled, match=r"^0 constraint rows for 9 unknowns: not a square system$"):
        compile_program(free)


def test_a_band_without_subdiagonal_holds_the_scaled_jacobian() -> None:
    """The crank of test_analysis.py driven at its centre's x: its band has kl = 0, so the store's first
    entry is a diagonal entry. Read back at the program's permuted positions the store is the plain
    scaled Jacobian (a bug this found: the slots off a row's pattern had store position 0, and the
    kernel wrote zeros there)."""
    scenario = dataclasses.replace(
        crank_scenario(), drivers=(AbsoluteDriver("drive", "crank", "x", Constant(0.05)),)
    )
    system = ConstraintSystem(scenario)
    p = compile_program(system)
    n, kl, w = p.n, int(p.sizes[S_KL]), int(p.sizes[S_WIDTH])
    assert kl == 0
    q = np.array([0.05, 0.08, 1.0])
    store = np.full(n * w, np.nan)
    work, jac = np.empty((5, WIDTH)), np.empty((2, 2, WIDTH))
    evaluate(
        p.ints, p.reals, q, np.zeros(n), 0.0, np.empty(n), np.empty(n), store, work, jac, np.empty((0, 4, 2))
    )
    read = permuted_band(store, p.perm, n, kl, w)
    expected = system.scaled_jacobian(system.jacobian(q, 0.0))
    np.testing.assert_allclose(read, expected, rtol=0, atol=1e-15)
