"""The generalized forces of gravity and the force elements (compiled.load_program) at one state, in
numba: the same composition as reference_solver.dynamics.loads, element by element, with the
potential energy, the power of the applied loads and the power the dampers dissipate."""

from __future__ import annotations

import math

from numba import njit

from reference_solver.compiled.evaluate import motion
from reference_solver.compiled.load_program import (
    FORCE,
    L_COL_I,
    L_COL_J,
    L_KIND,
    L_MOTION_1,
    L_MOTION_2,
    R_DAMPING,
    R_FREE,
    R_MOTION_1,
    R_MOTION_2,
    R_STIFFNESS,
    R_U_I,
    R_U_J,
    ROTATIONAL,
    SPRING,
    TORQUE,
)


@njit(cache=True, error_model="numpy", inline="always")
def _law(ints, reals, e, k_col, r_col, t):  # type: ignore[no-untyped-def]
    """The value at t of element e's motion in columns (k_col, r_col)."""
    return motion(
        ints[e, k_col], reals[e, r_col], reals[e, r_col + 1], reals[e, r_col + 2], reals[e, r_col + 3], t
    )[0]


@njit(cache=True, error_model="numpy", inline="always")
def _point(q, qd, col, ux, uy, out):  # type: ignore[no-untyped-def]
    """out <- the global position (0:2), velocity (2:4) and A u (4:6) of local point u on the body
    whose first column is col (-1: the ground, where the point is fixed)."""
    if col < 0:
        out[0], out[1], out[2], out[3], out[4], out[5] = ux, uy, 0.0, 0.0, 0.0, 0.0
        return
    c, s, w = math.cos(q[col + 2]), math.sin(q[col + 2]), qd[col + 2]
    ax, ay = c * ux - s * uy, s * ux + c * uy
    out[0], out[1] = q[col] + ax, q[col + 1] + ay
    out[2], out[3] = qd[col] - ay * w, qd[col + 1] + ax * w
    out[4], out[5] = ax, ay


@njit(cache=True, error_model="numpy", inline="always")
def _push(qe, col, fx, fy, ax, ay):  # type: ignore[no-untyped-def]
    """Add the force (fx, fy) acting at the body point whose A u is (ax, ay)."""
    if col >= 0:
        qe[col] += fx
        qe[col + 1] += fy
        qe[col + 2] += -ay * fx + ax * fy


@njit(cache=True, error_model="numpy")
def loads(ints, reals, gravity, q, qd, t, qe, points, totals):  # type: ignore[no-untyped-def]
    """qe <- Q_e(q, qd, t); totals <- potential energy, applied power, dissipated power; points
    (2, 6) is scratch."""
    potential, applied, dissipation = 0.0, 0.0, 0.0
    for i in range(qe.size):
        qe[i] = gravity[i]
        potential -= gravity[i] * q[i]
    for e in range(ints.shape[0]):
        kind, a, b = ints[e, L_KIND], ints[e, L_COL_I], ints[e, L_COL_J]
        if kind in (TORQUE, ROTATIONAL):
            angle = (q[b + 2] if b >= 0 else 0.0) - (q[a + 2] if a >= 0 else 0.0)
            rate = (qd[b + 2] if b >= 0 else 0.0) - (qd[a + 2] if a >= 0 else 0.0)
            if kind == TORQUE:  # +T on the body (a), -T on the reaction (b)
                torque = _law(ints, reals, e, L_MOTION_1, R_MOTION_1, t)
                applied -= torque * rate
            else:  # +T on body i (a), -T on body j (b)
                stretch = angle - reals[e, R_FREE]
                torque = reals[e, R_STIFFNESS] * stretch + reals[e, R_DAMPING] * rate
                potential += 0.5 * reals[e, R_STIFFNESS] * stretch**2
                dissipation += reals[e, R_DAMPING] * rate**2
            if a >= 0:
                qe[a + 2] += torque
            if b >= 0:
                qe[b + 2] -= torque
        elif kind == FORCE:
            fx = _law(ints, reals, e, L_MOTION_1, R_MOTION_1, t)
            fy = _law(ints, reals, e, L_MOTION_2, R_MOTION_2, t)
            _point(q, qd, a, reals[e, R_U_I], reals[e, R_U_I + 1], points[0])
            _push(qe, a, fx, fy, points[0, 4], points[0, 5])
            applied += fx * points[0, 2] + fy * points[0, 3]
        elif kind == SPRING:
            _point(q, qd, a, reals[e, R_U_I], reals[e, R_U_I + 1], points[0])
            _point(q, qd, b, reals[e, R_U_J], reals[e, R_U_J + 1], points[1])
            dx, dy = points[1, 0] - points[0, 0], points[1, 1] - points[0, 1]
            length = math.hypot(dx, dy)
            ux, uy = dx / length, dy / length
            rate = ux * (points[1, 2] - points[0, 2]) + uy * (points[1, 3] - points[0, 3])
            stretch = length - reals[e, R_FREE]
            tension = reals[e, R_STIFFNESS] * stretch + reals[e, R_DAMPING] * rate
            _push(qe, a, tension * ux, tension * uy, points[0, 4], points[0, 5])
            _push(qe, b, -tension * ux, -tension * uy, points[1, 4], points[1, 5])
            potential += 0.5 * reals[e, R_STIFFNESS] * stretch**2
            dissipation += reals[e, R_DAMPING] * rate**2
    totals[0], totals[1], totals[2] = potential, applied, dissipation
