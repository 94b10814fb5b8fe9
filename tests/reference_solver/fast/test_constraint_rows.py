"""The compiled rows of every constraint kind of the vocabulary against the plain path's equations:
C, C_q, Q_d and C_t of one scenario holding each kind (cams on all three profiles, an internal gear
on a carrier, non-unit axes and normals, offsets, every motion law) at random states, to 1e-12."""

from __future__ import annotations

import math

import numpy as np
import pytest

import scenarios
from reference_solver.fast.constraint_rows import NotCompiled, constraint_rows_of
from reference_solver.fast.evaluate import c_t, evaluate, profile_points
from reference_solver.fast.program import S_BODIES, S_KL, S_WIDTH, WIDTH, compile_dense, compile_program
from reference_solver.system import ConstraintSystem
from scenarios import GROUND, Point
from scenarios.bodies import Body
from scenarios.cam_profiles import EccentricDisc, LobedProfile, SplineProfile
from scenarios.cams import FlatFaceCam, KnifeEdgeCam, RollerCam
from scenarios.drivers import (
    AbsoluteDriver,
    PointPathDriver,
    RelativeDisplacementDriver,
    RelativeRotationDriver,
)
from scenarios.gears import GearPair, RackPinion
from scenarios.joints import Ground, Prismatic, Revolute, RevoluteRevolute
from scenarios.motions import Constant, ConstantSpeed, Harmonic
from scenarios.scenario import Scenario

NAMES = (
    "link",
    "slider",
    "gear1",
    "gear2",
    "carrier",
    "pinion",
    "rack",
    "cam1",
    "cam2",
    "cam3",
    "knife",
    "roller",
    "face",
)
DISC = EccentricDisc(0.05, 0.01)
VOCABULARY = Scenario(
    family="vocabulary",
    variant="default",
    bodies=tuple(Body(name, (0.0, 0.0, 0.0)) for name in NAMES),
    joints=(
        Ground("g", "carrier", (0.1, -0.2, 0.3)),
        Revolute("r0", Point(GROUND, (0.5, 0.2)), Point("link", (0.1, -0.3))),
        Revolute("r", Point("link", (0.3, 0.1)), Point("slider", (-0.2, 0.05))),
        Prismatic("p", Point("link", (0.1, 0.2)), Point("slider", (0.3, -0.1)), axis=(3.0, 4.0), angle=0.25),
        Prismatic("p0", Point(GROUND, (0.2, 0.1)), Point("rack", (0.3, -0.1)), axis=(0.0, 2.0), angle=-0.5),
        RevoluteRevolute("rr", Point("slider", (0.2, 0.1)), Point("gear1", (0.05, 0.0)), length=0.7),
        GearPair("gp", "gear1", 0.2, "gear2", 0.5, "carrier", True, 0.1, -0.2, 0.3),
        GearPair("gp0", "gear2", 0.3, "pinion", 0.1, theta0_i=0.4, theta0_j=0.7),
        RackPinion("rp", Point("pinion", (0.01, 0.02)), 0.1, Point("rack", (0.2, -0.1)), (1.0, 2.0), 0.03),
        KnifeEdgeCam("k", "cam1", DISC, Point("knife", (0.02, -0.01)), 0.3),
        RollerCam("rc", "cam2", SplineProfile.sample(DISC, 12), Point("roller", (0.01, 0.03)), 0.015, 1.0),
        FlatFaceCam("f", "cam3", LobedProfile(0.05, 0.01, 3), Point("face", (0.02, 0.01)), (0.0, -2.0), 2.0),
    ),
    drivers=(
        AbsoluteDriver("ax", "link", "x", ConstantSpeed(0.2, 1.5)),
        AbsoluteDriver("ay", "slider", "y", Harmonic(0.1, 0.3, 2.0, 0.5)),
        AbsoluteDriver("at", "cam1", "theta", Constant(0.7)),
        RelativeRotationDriver("rot", "gear2", "cam2", Harmonic(-0.2, 0.4, 3.0)),
        PointPathDriver(
            "path", Point("face", (0.1, 0.2)), ConstantSpeed(-0.3, 0.5), Harmonic(0.0, 0.2, 1.0, 1.0)
        ),
        RelativeDisplacementDriver(
            "disp",
            Point("knife", (0.1, 0.0)),
            Point("cam3", (0.0, 0.2)),
            Constant(0.05),
            ConstantSpeed(0.1, -2.0),
        ),
    ),
    t_end=1.0,
    steps=10,
    characteristic_length=0.5,
)


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
    with pytest.raises(NotCompiled, match=r"^no fast kernel for str$"):
        constraint_rows_of("a revolute")  # type: ignore[arg-type]
    with pytest.raises(NotCompiled, match=r"^no fast kernel for motion float$"):
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
    read = np.zeros((n, n))
    for i in range(n):
        for slot in range(w):
            j = i - kl + slot
            if 0 <= j < n:
                read[p.perm[0, i], p.perm[1, j]] = store[i * w + slot]
    expected = system.scaled_jacobian(system.jacobian(q, 0.3))
    assert np.max(np.abs(expected)) > 2.0  # the scales matter: L = 0.05 m here
    np.testing.assert_allclose(read, expected, rtol=0, atol=1e-12 * np.max(np.abs(expected)))
