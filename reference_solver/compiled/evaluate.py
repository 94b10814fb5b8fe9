"""C, the scaled C_q (into the band store), C_t and Q_d of a compiled program, in numba.

Row by row, the same composition as kinematic_vectors: each term adds its value, Jacobian over the
row's local slots, time derivative and velocity-dependent acceleration to vector A or B; the row is
a component of A or A . B, plus its linear terms, minus its constant and its motion f(t).
A vector sums its positions (body origins and ground points) apart from its rotated parts and adds
the two at the end: (x_i - x_j) + (A_i u_i - A_j u_j), whose round-off is that of link-sized
quantities, not (x_i + A_i u_i) - (x_j + A_j u_j), which loses the round-off of the coordinates
themselves (9e-15 on A02's 40 m chain) to cancellation.
Everything comes in as separate arrays and is indexed in place: no views, no containers, so numba
needs no (atomic) reference counting in the loops.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from reference_solver.compiled.constraint_rows import (
    COMPONENT_X,
    COMPONENT_Y,
    DIRECTION,
    INNER,
    POINT,
    PROFILE_POINT,
)
from reference_solver.compiled.program import (
    DISC,
    K_KIND,
    K_MOTION,
    K_REUSE,
    K_SLOT_COL,
    K_SLOT_POS,
    K_TERM_COL,
    K_TERM_PHI,
    K_TERM_PHI_SLOT,
    K_TERM_SLOT,
    K_TERM_TYPE,
    K_WIDTH,
    LOBED,
    MOTION_CONSTANT,
    MOTION_HARMONIC,
    MOTION_LINEAR,
    TERMS,
    X_CONSTANT,
    X_LINEAR,
    X_MOTION,
    X_SLOT_SCALE,
    X_TERM_SIGN,
    X_TERM_U,
)
from scenarios.cam_profiles import disc_radii, lobed_radii

COS, SIN, VECTOR, ROW = 0, 1, 2, 4
"""Rows of evaluate's scratch `work`: VECTOR and VECTOR + 1 hold vectors A and B."""
POSITION = 6
"""Columns POSITION, POSITION + 1 of a vector's row: the sum of its positions, kept apart (above)."""


@njit(cache=True, error_model="numpy", inline="always")
def motion(kind: int, p0: float, p1: float, p2: float, p3: float, t: float) -> tuple[float, float, float]:
    """f(t), f'(t), f''(t) of scenarios.motions."""
    if kind == MOTION_LINEAR:
        return p0 + p1 * t, p1, 0.0
    if kind == MOTION_HARMONIC:
        arg = p2 * t + p3
        return p0 + p1 * math.cos(arg), -p1 * p2 * math.sin(arg), -p1 * p2**2 * math.cos(arg)
    if kind == MOTION_CONSTANT:
        return p0, 0.0, 0.0
    return 0.0, 0.0, 0.0


_disc_radii = njit(cache=True, error_model="numpy", inline="always")(disc_radii)
_lobed_radii = njit(cache=True, error_model="numpy", inline="always")(lobed_radii)


@njit(cache=True, error_model="numpy", inline="always")
def radii(profiles, splines, contact, phi):  # type: ignore[no-untyped-def]
    """d(phi) and its first three derivatives of the contact's profile (scenarios.cam_profiles)."""
    if profiles[contact, 0] == DISC:
        return _disc_radii(profiles[contact, 3], profiles[contact, 4], phi)
    if profiles[contact, 0] == LOBED:
        return _lobed_radii(profiles[contact, 3], profiles[contact, 4], profiles[contact, 1], phi)
    period = 2.0 * math.pi
    p = np.fmod(phi, period)
    if p < 0.0:
        p += period
    first, count = int(profiles[contact, 1]), int(profiles[contact, 2])
    low, high = 0, count - 1  # the interval with knot <= p < next knot, as scipy's PPoly finds it
    while low < high:
        middle = (low + high + 1) // 2
        if splines[first + middle, 0] <= p:
            low = middle
        else:
            high = middle - 1
    k = first + low
    h, c0, c1, c2, c3 = p - splines[k, 0], splines[k, 1], splines[k, 2], splines[k, 3], splines[k, 4]
    return (
        c0 + h * (c1 + h * (c2 + h * c3)),
        c1 + h * (2.0 * c2 + 3.0 * h * c3),
        2.0 * c2 + 6.0 * h * c3,
        6.0 * c3,
    )


@njit(cache=True, error_model="numpy", inline="always")
def _polar(us: np.ndarray, contact: int, k: int, radial: float, normal: float, c: float, s: float) -> None:
    """us[contact, k] <- radial e_r + normal e_n, with e_r = (c, s) and e_n = (-s, c)."""
    us[contact, k, 0] = radial * c - normal * s
    us[contact, k, 1] = radial * s + normal * c


@njit(cache=True, error_model="numpy")
def profile_points(profiles, splines, q, bodies, us):  # type: ignore[no-untyped-def]
    """us[c, k] <- the k-th derivative, k = 0..3, of d(phi) [cos phi, sin phi] for contact c's
    profile at its parameter phi in q."""
    for contact in range(profiles.shape[0]):
        phi = q[3 * bodies + contact]
        d0, d1, d2, d3 = radii(profiles, splines, contact, phi)
        c, s = math.cos(phi), math.sin(phi)
        _polar(us, contact, 0, d0, 0.0, c, s)
        _polar(us, contact, 1, d1, d0, c, s)
        _polar(us, contact, 2, d2 - d0, 2.0 * d1, c, s)
        _polar(us, contact, 3, d3 - 3.0 * d1, 3.0 * d2 - d0, c, s)


@njit(cache=True, error_model="numpy")
def evaluate(ints, reals, q, qd, t, c, q_d, band, work, jac, us):  # type: ignore[no-untyped-def]
    """c <- C(q, t), q_d <- Q_d(q, qd, t) and, unless `band` is empty, band <- the scaled C_q
    (original entries, before any factorization). us (contacts, 4, 2) holds the profile points at q
    (`profile_points`); work (5, max(bodies, WIDTH)) and jac (2, 2, WIDTH) are scratch: work holds
    cos and sin of each body's angle, vectors A and B (value 0:2, rate 2:4, velocity-dependent
    acceleration 4:6, the value's positions 6:8) and the row's Jacobian; jac the Jacobians of A and B.
    It calls nothing: a call would keep numba from pruning the reference counts of the arguments."""
    n, bodies = ints.shape[0], (q.size - us.shape[0]) // 3
    for b in range(bodies):
        work[COS, b], work[SIN, b] = math.cos(q[3 * b + 2]), math.sin(q[3 * b + 2])
    with_jacobian = band.size > 0
    for i in range(band.size):
        band[i] = 0.0
    for r in range(n):
        kind, width = ints[r, K_KIND], ints[r, K_WIDTH]
        value, acc = 0.0, 0.0
        for s in range(width):
            work[ROW, s] = 0.0
        if kind != 0:
            if not ints[r, K_REUSE]:
                _vectors(ints, reals, q, qd, work, jac, us, r, width, bodies)
            if kind in (COMPONENT_X, COMPONENT_Y):
                axis = kind - COMPONENT_X
                value, acc = work[VECTOR, axis], -work[VECTOR, 4 + axis]
                for s in range(width):
                    work[ROW, s] = jac[0, axis, s]
            elif kind == INNER:
                ax, ay, bx, by = work[VECTOR, 0], work[VECTOR, 1], work[VECTOR + 1, 0], work[VECTOR + 1, 1]
                value = ax * bx + ay * by
                acc = -(
                    work[VECTOR, 4] * bx
                    + work[VECTOR, 5] * by
                    + 2.0 * (work[VECTOR, 2] * work[VECTOR + 1, 2] + work[VECTOR, 3] * work[VECTOR + 1, 3])
                )
                acc -= ax * work[VECTOR + 1, 4] + ay * work[VECTOR + 1, 5]
                for s in range(width):
                    work[ROW, s] = (
                        jac[0, 0, s] * bx + jac[0, 1, s] * by + jac[1, 0, s] * ax + jac[1, 1, s] * ay
                    )
        for s in range(width):
            coefficient = reals[r, X_LINEAR + s]
            if coefficient != 0.0:
                value += coefficient * q[ints[r, K_SLOT_COL + s]]
                work[ROW, s] += coefficient
        f, _, ddf = row_motion(ints, reals, r, t)
        c[r] = value - reals[r, X_CONSTANT] - f
        q_d[r] = acc + ddf
        if with_jacobian:
            for s in range(width):
                pos = ints[r, K_SLOT_POS + s]
                if pos >= 0:
                    band[pos] = work[ROW, s] * reals[r, X_SLOT_SCALE + s]


@njit(cache=True, error_model="numpy", inline="always")
def row_motion(ints, reals, r, t):  # type: ignore[no-untyped-def]
    """f(t), f'(t), f''(t) of row r's motion (zero for a row without one)."""
    return motion(
        ints[r, K_MOTION],
        reals[r, X_MOTION],
        reals[r, X_MOTION + 1],
        reals[r, X_MOTION + 2],
        reals[r, X_MOTION + 3],
        t,
    )


@njit(cache=True, error_model="numpy", inline="always")
def _vectors(ints, reals, q, qd, work, jac, us, r, width, bodies):  # type: ignore[no-untyped-def]
    """Vectors A and B of row r into work[VECTOR + v] and their Jacobians over the row's local
    slots into jac[v], v = 0, 1."""
    for v in range(2):
        for i in range(POSITION + 2):
            work[VECTOR + v, i] = 0.0
        for s in range(width):
            jac[v, 0, s], jac[v, 1, s] = 0.0, 0.0
    for k in range(TERMS):
        term = ints[r, K_TERM_TYPE + k]
        if term == 0:
            continue
        v, sign = k // 2, reals[r, X_TERM_SIGN + k]
        col, slot = ints[r, K_TERM_COL + k], ints[r, K_TERM_SLOT + k]
        cs, sn, w = 1.0, 0.0, 0.0
        if col >= 0:
            cs, sn, w = work[COS, col // 3], work[SIN, col // 3], qd[col + 2]
        if term in (POINT, DIRECTION):
            ux, uy = reals[r, X_TERM_U + 2 * k], reals[r, X_TERM_U + 2 * k + 1]
            ax, ay = cs * ux - sn * uy, sn * ux + cs * uy
            work[VECTOR + v, 2] += sign * -ay * w
            work[VECTOR + v, 3] += sign * ax * w
            work[VECTOR + v, 4] += sign * -ax * w * w
            work[VECTOR + v, 5] += sign * -ay * w * w
        else:
            phi_col, phi_slot = ints[r, K_TERM_PHI + k], ints[r, K_TERM_PHI_SLOT + k]
            contact, d = phi_col - 3 * bodies, 0 if term == PROFILE_POINT else 1
            ax = cs * us[contact, d, 0] - sn * us[contact, d, 1]
            ay = sn * us[contact, d, 0] + cs * us[contact, d, 1]
            bx = cs * us[contact, d + 1, 0] - sn * us[contact, d + 1, 1]
            by = sn * us[contact, d + 1, 0] + cs * us[contact, d + 1, 1]
            ex = cs * us[contact, d + 2, 0] - sn * us[contact, d + 2, 1]
            ey = sn * us[contact, d + 2, 0] + cs * us[contact, d + 2, 1]
            rate = qd[phi_col]
            work[VECTOR + v, 2] += sign * (-ay * w + bx * rate)
            work[VECTOR + v, 3] += sign * (ax * w + by * rate)
            work[VECTOR + v, 4] += sign * (-ax * w * w - 2.0 * by * w * rate + ex * rate * rate)
            work[VECTOR + v, 5] += sign * (-ay * w * w + 2.0 * bx * w * rate + ey * rate * rate)
            jac[v, 0, phi_slot] += sign * bx
            jac[v, 1, phi_slot] += sign * by
        at = POSITION if col < 0 and term == POINT else 0  # a ground point is a position
        work[VECTOR + v, at] += sign * ax
        work[VECTOR + v, at + 1] += sign * ay
        if slot >= 0:
            jac[v, 0, slot + 2] += sign * -ay
            jac[v, 1, slot + 2] += sign * ax
            if term in (POINT, PROFILE_POINT):
                work[VECTOR + v, POSITION] += sign * q[col]
                work[VECTOR + v, POSITION + 1] += sign * q[col + 1]
                work[VECTOR + v, 2] += sign * qd[col]
                work[VECTOR + v, 3] += sign * qd[col + 1]
                jac[v, 0, slot] += sign
                jac[v, 1, slot + 1] += sign
    for v in range(2):
        work[VECTOR + v, 0] += work[VECTOR + v, POSITION]
        work[VECTOR + v, 1] += work[VECTOR + v, POSITION + 1]


@njit(cache=True, error_model="numpy", inline="always")
def c_t(ints, reals, t, out):  # type: ignore[no-untyped-def]
    """out <- C_t = -f'(t) per row."""
    for r in range(ints.shape[0]):
        m = X_MOTION
        out[r] = -motion(
            ints[r, K_MOTION], reals[r, m], reals[r, m + 1], reals[r, m + 2], reals[r, m + 3], t
        )[1]
