"""The instruction table: a scenario's constraint rows compiled into flat arrays for the kernels.

Columns, row scales and the local column slots of each row come from the plain path's
ConstraintSystem, so both paths number and scale the unknowns the same way. Each row has up to
WIDTH local slots (three per moving body it touches, then the cam parameter) and up to four terms
(two for vector A, two for B), stored in one integer and one real array with the column offsets
below. Profiles and motions become codes with parameters.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from reference_solver.compiled.constraint_rows import (
    COMPONENT_X,
    COMPONENT_Y,
    POINT,
    PROFILE_POINT,
    PROFILE_TANGENT,
    ConstraintRowSpec,
    NotCompiled,
    Term,
    constraint_rows_of,
)
from reference_solver.compiled.structure import Band, StructurallySingular, band_of
from reference_solver.equation import Equation
from reference_solver.system import ConstraintSystem
from scenarios.cam_profiles import EccentricDisc, LobedProfile, Profile, SplineProfile
from scenarios.motions import Constant, ConstantSpeed, Harmonic, Motion

WIDTH = 10
TERMS = 4
DISC, SPLINE, LOBED = 0, 1, 2
MOTION_NONE, MOTION_LINEAR, MOTION_HARMONIC, MOTION_CONSTANT = 0, 1, 2, 3
# Integer columns of a row.
K_KIND, K_REUSE, K_WIDTH, K_MOTION = 0, 1, 2, 3  # K_REUSE: vectors A and B as in the row before
K_SLOT_COL = 4  # WIDTH columns: the global column of each local slot, -1 unused
K_SLOT_POS = K_SLOT_COL + WIDTH  # WIDTH: index in the band store, -1 outside the pattern
K_TERM_TYPE = K_SLOT_POS + WIDTH  # TERMS each: 0 none, then POINT .. PROFILE_TANGENT
K_TERM_COL = K_TERM_TYPE + TERMS  # first global column of the term's body, -1 ground
K_TERM_SLOT = K_TERM_COL + TERMS  # first local slot of the body, -1 ground
K_TERM_PHI = K_TERM_SLOT + TERMS  # global column of the contact parameter
K_TERM_PHI_SLOT = K_TERM_PHI + TERMS
INT_COLUMNS = K_TERM_PHI_SLOT + TERMS
# Real columns of a row.
X_CONSTANT = 0
X_MOTION = 1  # 4 motion parameters
X_LINEAR = X_MOTION + 4  # WIDTH: coefficient per local slot
X_SLOT_SCALE = X_LINEAR + WIDTH  # WIDTH: column scale / row scale
X_TERM_SIGN = X_SLOT_SCALE + WIDTH  # TERMS
X_TERM_U = X_TERM_SIGN + TERMS  # 2 per term: local coordinates
REAL_COLUMNS = X_TERM_U + 2 * TERMS
# Entries of `sizes`.
S_N, S_BODIES, S_KL, S_KU, S_WIDTH = range(5)


class Program(NamedTuple):
    """The arrays the kernels read, passed to them one by one (numba then needs no reference counts)."""

    ints: np.ndarray  # (n, INT_COLUMNS) per row
    reals: np.ndarray  # (n, REAL_COLUMNS) per row
    scales: np.ndarray  # (2, n): row scales, column scales
    perm: np.ndarray  # (2, n): band row i is original row perm[0, i], band column j column perm[1, j]
    sizes: np.ndarray  # n, moving bodies, band kl and ku, band store row width
    parity: float  # sign of both permutations: det(band matrix) = parity det(C_q)
    profiles: np.ndarray  # (contacts, 5) per cam contact: kind, first spline row, intervals, R, e
    splines: np.ndarray  # (K, 5) knot, then d, d', d''/2, d'''/6 of the interval starting there

    @property
    def n(self) -> int:
        return int(self.sizes[S_N])


def motion_code(motion: Motion | None) -> tuple[int, tuple[float, ...]]:
    if motion is None:
        return MOTION_NONE, ()
    if isinstance(motion, ConstantSpeed):
        return MOTION_LINEAR, (motion.start, motion.rate)
    if isinstance(motion, Harmonic):
        return MOTION_HARMONIC, (motion.mean, motion.amplitude, motion.omega, motion.phase)
    if isinstance(motion, Constant):
        return MOTION_CONSTANT, (motion.value,)
    raise NotCompiled(f"no compiled kernel for motion {type(motion).__name__}")


def spline_rows(profile: SplineProfile) -> np.ndarray:
    """Per interval of the periodic spline: its left knot, then d, d', d''/2, d'''/6 there, the profile's
    own local cubic (SplineProfile.pieces, so the kernel reproduces it); a last row holds the closing knot."""
    count = len(profile.table)
    rows = np.zeros((count + 1, 5))
    rows[:, 0] = np.linspace(0.0, 2.0 * math.pi, count + 1)
    rows[:count, 1:] = profile.pieces
    return rows


def profile_tables(profiles: list[Profile]) -> tuple[np.ndarray, np.ndarray]:
    """The `profiles` and `splines` arrays of a program, for the contacts' profiles in order."""
    table = np.zeros((len(profiles), 5))
    blocks: list[np.ndarray] = [np.zeros((0, 5))]
    first: dict[Profile, int] = {}
    for contact, profile in enumerate(profiles):
        if isinstance(profile, EccentricDisc):
            table[contact] = (DISC, 0, 0, profile.radius, profile.eccentricity)
        elif isinstance(profile, SplineProfile):
            if profile not in first:
                first[profile] = sum(len(b) for b in blocks)
                blocks.append(spline_rows(profile))
            table[contact] = (SPLINE, first[profile], len(profile.table), 0.0, 0.0)
        elif isinstance(profile, LobedProfile):
            table[contact] = (LOBED, profile.lobes, 0, profile.radius, profile.amplitude)
        else:
            raise NotCompiled(f"no compiled kernel for profile {type(profile).__name__}")
    return table, np.concatenate(blocks)


def _pattern(spec: ConstraintRowSpec, eq: Equation, linear: np.ndarray) -> set[int]:
    """The local slots where the row's Jacobian can be non-zero."""
    slots = {int(s) for s in np.flatnonzero(linear)}
    for term in spec.a + spec.b:
        slot = eq.local(term.body)
        if slot is not None:
            slots.add(slot + 2)
            if term.kind in (POINT, PROFILE_POINT):
                axes = (0,) if spec.kind == COMPONENT_X else (1,) if spec.kind == COMPONENT_Y else (0, 1)
                slots.update(slot + a for a in axes)
        if term.kind in (PROFILE_POINT, PROFILE_TANGENT):
            assert eq.phi_local is not None
            slots.add(eq.phi_local)
    return slots


def _padded(spec: ConstraintRowSpec) -> tuple[Term | None, ...]:
    if len(spec.a) > 2 or len(spec.b) > 2:
        raise NotCompiled("a row vector has more than two terms")
    return (*(*spec.a, None, None)[:2], *(*spec.b, None, None)[:2])


class _Rows:
    """The per-row arrays, filled row by row."""

    def __init__(self, m: int):
        self.ints = np.zeros((m, INT_COLUMNS), np.int64)
        # Slots unused (-1 column) and slots off the row's pattern (-1 position: written nowhere).
        self.ints[:, K_SLOT_COL : K_SLOT_POS + WIDTH] = -1
        self.ints[:, K_TERM_COL : K_TERM_SLOT + TERMS] = -1
        self.reals = np.zeros((m, REAL_COLUMNS))
        self.patterns: list[set[int]] = []

    def add(self, r: int, spec: ConstraintRowSpec, eq: Equation, reuse: bool) -> None:
        ints, reals = self.ints[r], self.reals[r]
        ints[K_KIND], ints[K_REUSE], ints[K_WIDTH] = spec.kind, reuse, eq.width
        ints[K_MOTION], params = motion_code(spec.motion)
        reals[X_MOTION : X_MOTION + len(params)] = params
        reals[X_CONSTANT] = spec.constant
        ints[K_SLOT_COL : K_SLOT_COL + eq.width] = eq.columns
        for body, coordinate, coefficient in spec.linear:
            slot = eq.local(body)
            if slot is not None:
                reals[X_LINEAR + slot + coordinate] += coefficient
        for k, term in enumerate(_padded(spec)):
            if term is None:
                continue
            ints[K_TERM_TYPE + k], reals[X_TERM_SIGN + k] = term.kind, term.sign
            col, slot = eq.layout.body_column(term.body), eq.local(term.body)
            ints[K_TERM_COL + k] = -1 if col is None else col
            ints[K_TERM_SLOT + k] = -1 if slot is None else slot
            reals[X_TERM_U + 2 * k : X_TERM_U + 2 * k + 2] = term.local
            if term.contact is not None:
                assert eq.phi_local is not None
                ints[K_TERM_PHI + k] = eq.layout.phi_column(term.contact)
                ints[K_TERM_PHI_SLOT + k] = eq.phi_local
        self.patterns.append(_pattern(spec, eq, reals[X_LINEAR : X_LINEAR + WIDTH]))

    def place(self, band: Band | DenseStore | RowStore, row_scale: np.ndarray, col_scale: np.ndarray) -> None:
        """Each pattern slot's position in the band (or dense) store and its scale."""
        for r, slots in enumerate(self.patterns):
            for s in slots:
                col = int(self.ints[r, K_SLOT_COL + s])
                self.ints[r, K_SLOT_POS + s] = band.position(r, col)
                self.reals[r, X_SLOT_SCALE + s] = col_scale[col] / row_scale[r]


class DenseStore:
    """A row-major m x n store: where `evaluate` writes the unscaled C_q of a system that is not
    square (forward dynamics), entry (row, col) at row * n + col."""

    def __init__(self, columns: int) -> None:
        self.columns = columns

    def position(self, row: int, col: int) -> int:
        return row * self.columns + col


class RowStore:
    """An m x WIDTH store of the unscaled C_q row by row: row r's entry at its local slot s (column
    ints[r, K_SLOT_COL + s]) at r * WIDTH + s, so a kernel walking a sparse C_q (ALI3-P's) writes and
    reads only the entries a row can have."""

    def __init__(self, ints: np.ndarray) -> None:
        self.ints = ints

    def position(self, row: int, col: int) -> int:
        slots = [int(c) for c in self.ints[row, K_SLOT_COL : K_SLOT_COL + WIDTH]]
        return row * WIDTH + slots.index(col)


def compile_program(system: ConstraintSystem) -> Program:
    """The instruction table of a square constraint system; NotCompiled if it cannot have one."""
    m, n = system.size, system.unknowns
    if m != n or n == 0:
        raise NotCompiled(f"{m} constraint rows for {n} unknowns: not a square system")
    rows = _instruction_rows(system)
    entries = [
        (row, int(rows.ints[row, K_SLOT_COL + s])) for row, slots in enumerate(rows.patterns) for s in slots
    ]
    try:
        band = band_of(entries, n)
    except StructurallySingular as error:
        raise NotCompiled(str(error)) from None
    row_scale = np.asarray(system.row_scales, dtype=float)
    col_scale = np.asarray(system.column_scales, dtype=float)
    rows.place(band, row_scale, col_scale)
    profiles, splines = profile_tables([cam.profile for cam in system.scenario.cams])
    return Program(
        ints=rows.ints,
        reals=rows.reals,
        scales=np.stack([row_scale, col_scale]),
        perm=np.stack([band.row_perm, band.col_perm]).astype(np.int64),
        sizes=np.array([n, len(system.layout.bodies), band.kl, band.ku, band.width], np.int64),
        parity=band.parity,
        profiles=profiles,
        splines=splines,
    )


def compile_dense(system: ConstraintSystem, by_rows: bool = False) -> Program:
    """The instruction table of any constraint system with a DenseStore for its unscaled C_q (the
    band fields empty), or with `by_rows` a RowStore; NotCompiled if it cannot have one."""
    m, n = system.size, system.unknowns
    if m == 0 or n == 0:
        raise NotCompiled(f"{m} constraint rows for {n} unknowns: nothing to compile")
    rows = _instruction_rows(system)
    rows.place(RowStore(rows.ints) if by_rows else DenseStore(n), np.ones(m), np.ones(n))
    profiles, splines = profile_tables([cam.profile for cam in system.scenario.cams])
    return Program(
        ints=rows.ints,
        reals=rows.reals,
        scales=np.zeros((2, 0)),
        perm=np.zeros((2, 0), np.int64),
        sizes=np.array([n, len(system.layout.bodies), 0, 0, 0], np.int64),
        parity=1.0,
        profiles=profiles,
        splines=splines,
    )


def _instruction_rows(system: ConstraintSystem) -> _Rows:
    """Every constraint row of the system as instructions (their Jacobian slots not placed yet)."""
    rows = _Rows(system.size)
    constraints = system.scenario.joints + system.scenario.drivers
    r = 0
    for constraint, eq in zip(constraints, system.equations, strict=True):
        specs = constraint_rows_of(constraint)
        assert len(specs) == eq.size, constraint
        if eq.width > WIDTH:
            raise NotCompiled(f"{eq.name} touches {eq.width} columns, more than {WIDTH}")
        for number, spec in enumerate(specs):
            previous = specs[number - 1] if number else None
            rows.add(r, spec, eq, previous is not None and (previous.a, previous.b) == (spec.a, spec.b))
            r += 1
    return rows
