"""The compiled rows of every constraint kind of the vocabulary against the plain path's equations:
C, C_q, Q_d and C_t of one scenario holding each kind (cams on all three profiles, an internal gear
on a carrier, non-unit axes and normals, offsets, every motion law) at random states, to 1e-12."""

from __future__ import annotations

import math

import numpy as np
import pytest

import scenarios
from reference_solver.compiled.constraint_rows import NotCompiled, constraint_rows_of
from reference_solver.compiled.evaluate import c_t, evaluate, profile_points
from reference_solver.compiled.program import S_BODIES, S_KL, S_WIDTH, WIDTH, compile_dense, compile_program
from reference_solver.system import ConstraintSystem
from scenarios.drivers import (
    AbsoluteDriver,
)
from scenarios.scenario import Scenario
from tests.support.band_store import permuted_band
from tests.support.vocabulary import NAMES, VOCABULARY


def _compiled_rows(system: ConstraintSystem, q: np.ndarray, qd: np.ndarray, t: float):  # type: ignore[no-untyped-def]
    """C, the dense C_q, Q_d and C_t of the compiled program at (q, qd, t)."""
    p = compile_dense(system)
    m, n, contacts = system.size, system.unknowns, p.profiles.shape[0]
    c, q_d, store, ct = np.empty(m), np.empty(m), np.full(m * n, np.nan), np.empty(m)
    us = np.empty((contacts, 4, 2))
    profile_points(p.profiles, p.splines, q, (n - contacts) // 3, us)
    work, jac = np.empty((5, max(len(NAMES), WIDTH))), np.empty((2, 2, WIDTH))
    evaluate(p.ints, p.reals, q, qd, t, c, q_d, store, work, jac, us)
    c_t(p.ints, p.reals, t, ct)
    return c, store.reshape(m, n), q_d, ct


def test_every_row_kind_is_the_plain_row() -> None:
    system = ConstraintSystem(VOCABULARY)
    assert system.size == 29 and system.unknowns == 42  # 21 joint rows, 8 driver rows
    rng = np.random.default_rng(11)
    for _ in range(8):
        q, qd, t = (
            rng.uniform(-1, 1, system.unknowns),
            rng.normal(size=system.unknowns),
            float(rng.uniform(0, 2)),
        )
        expected = (*system.evaluate(q, t, qd), system.c_t(t))
        for level, mine, theirs in zip(
            ("C", "C_q", "Q_d", "C_t"), _compiled_rows(system, q, qd, t), expected, strict=True
        ):
            np.testing.assert_allclose(
                mine, theirs, rtol=0, atol=1e-12 * max(1.0, np.max(np.abs(theirs))), err_msg=level
            )


def test_a_constraint_or_motion_without_a_kernel_is_named() -> None:
    with pytest.raises(NotCompiled, match=r"^no compiled kernel for str$"):
        constraint_rows_of("a revolute")  # type: ignore[arg-type]
    with pytest.raises(NotCompiled, match=r"^no compiled kernel for motion float$"):
        compile_dense(ConstraintSystem(_with_driver(AbsoluteDriver("a", "link", "x", math.pi))))  # type: ignore[arg-type]


def _with_driver(driver: AbsoluteDriver) -> Scenario:
    from dataclasses import replace

    return replace(VOCABULARY, drivers=(driver,))


def test_the_band_store_holds_the_scaled_jacobian() -> None:
    """On a square scenario the kernel writes D_r^-1 C_q D_c (rows over L^power, lengths over L) into
    the band store at the program's permuted positions: read back, it is the plain scaled Jacobian."""
    scenario = scenarios.build("cam_roller/spline")
    system = ConstraintSystem(scenario)
    p = compile_program(system)
    n, kl, w = p.n, int(p.sizes[S_KL]), int(p.sizes[S_WIDTH])
    rng = np.random.default_rng(5)
    q = system.layout.initial_guess(scenario) + 0.1 * rng.normal(size=n)
    store, us = np.full(n * w, np.nan), np.empty((p.profiles.shape[0], 4, 2))
    profile_points(p.profiles, p.splines, q, int(p.sizes[S_BODIES]), us)
    work, jac = np.empty((5, max(int(p.sizes[S_BODIES]), WIDTH))), np.empty((2, 2, WIDTH))
    evaluate(p.ints, p.reals, q, np.zeros(n), 0.3, np.empty(n), np.empty(n), store, work, jac, us)
    read = permuted_band(store, p.perm, n, kl, w)
    expected = system.scaled_jacobian(system.jacobian(q, 0.3))
    assert np.max(np.abs(expected)) > 2.0  # the scales matter: L = 0.05 m here
    np.testing.assert_allclose(read, expected, rtol=0, atol=1e-12 * np.max(np.abs(expected)))
