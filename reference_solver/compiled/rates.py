"""One right-hand side of the coordinate-partitioned forward dynamics in a single numba call: the
steps of reference_solver.dynamics.partition (positions, rates, state) over the compiled
constraint rows (compiled.evaluate), force elements (compiled.load_kernel) and small dense LU
(compiled.dense_lu).

    positions  from the anchor (the configuration of the integrator's last accepted step), the
               tangent predictor C_D dq_D = -(C_I dq_I + C_t(t) - C_t(t_anchor)), then Newton on
               the dependent coordinates until C holds to RESIDUAL (scaled) or stalls below STALLED;
               its corrections use the anchor's LU of C_D (a chord method) while each cuts the
               residual to CHORD_CONTRACTION of the one before, C_D's own LU from the first one
               that does not (the plain path factors at every iteration); C_D is factored where
               Newton stops, for what follows
    rates      C_D q'_D = -C_t - C_I q'_I
    state      Q_d, Q_e, and q'', lambda from M q'' + C_q^T lambda = Q_e, C_q q'' = Q_d, reduced to
               the independent accelerations through C_D's LU (the plain path solves the augmented
               matrix whole: each checks the other)

`partitioned` does them up to `level` and keeps the converged q, C_q and LU of C_D in its
arguments; `anchor` makes them the next calls' start once the integrator accepts a step, as
Partitioned does in its attributes. Starting every call from the last evaluation instead let a
rejected trial stage far off the motion (slider_crank_spring/undamped at rtol 1e-6: the crank's
rate 1764 rad/s in a stage against 92 in the step before) carry Newton onto the mechanism's other
assembly for every later stage. Every array is made by the
caller (compiled.rates' caller, dynamics.compiled_rates); the rows of `vec` are the vectors below.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from reference_solver.compiled.dense_lu import lu_factor, lu_solve, lu_solve_transposed
from reference_solver.compiled.evaluate import c_t, evaluate
from reference_solver.compiled.load_kernel import loads

POSITIONS, STATE, RATES = 0, 1, 2
"""Levels: how far `partitioned` goes."""
OK, NOT_CONVERGED, SINGULAR = 0, 1, 2
(
    Q,
    QT,
    QD,
    QDD,
    QE,
    LAM,
    ZERO,
    GRAVITY,
    MASS,
    ROW_SCALE,
    COL_SCALE,
    C,
    Q_D,
    CT,
    CT_LAST,
    MOVE,
    RHS,
    TOTALS,
    TOL,
    Q_ANCHOR,
    CT_ANCHOR,
    TIMES,
) = range(22)
CHORD_CONTRACTION = 0.01
"""A chord step must cut Newton's residual to this fraction or less, else C_D is factored anew
(measured: a fresh chord contracts by 1e-3 to 2e-3 a step; after a long jump of the integrator's
trial state, by 0.09, which ran out of iterations at 1.2e-14 on four_bar_gravity)."""
VECTORS = 22
"""Rows of `vec`, each n + m long: Q the last converged positions, QT Newton's iterate, TOTALS the
potential energy, applied power and dissipation of the last state, TOL Newton's (RESIDUAL, STALLED),
Q_ANCHOR and CT_ANCHOR the anchor's q and C_t, TIMES the time of Q (entry 0)."""
IND, DEP, SIZES, PIV, PIV_TRIAL, RPIV, PIV_ANCHOR = range(7)
INDICES = 7
"""Rows of `index`: the independent and dependent columns, the sizes below, the row swaps of the
LU factors in `mats` (LU, LU_TRIAL and LU_ANCHOR) and of the reduced mass matrix."""
S_N, S_M, S_F, S_DRIVERS, S_NEWTON, S_HAS_FACTORS, S_CHORD = range(7)
"""Entries of index[SIZES]: coordinates, rows, independent coordinates, first driver row, Newton's
iteration limit, whether the anchor has factors (the predictor's), and whether Newton may correct
with them (the chord; 0: C_D factored at every iteration, as the plain path does)."""
LAST, TRIAL, ANCHOR = 0, 1, 2
JACOBIANS = 3
"""The slots of `jacs`: the last converged C_q, Newton's and the anchor's (flat, row-major)."""
LU, LU_TRIAL, REDUCED, X, LU_ANCHOR = range(5)
MATRICES = 5
"""Slots of `mats`, each max(m, f) square: C_D's last converged LU factors and Newton's, the reduced
mass matrix, X = C_D^-1 C_I and the anchor's LU factors of C_D."""
POINTS = 5
"""Rows POINTS, POINTS + 1 of `work` (after evaluate's) hold the load kernel's point scratch."""


@njit(cache=True, error_model="numpy", inline="always")
def _scaled_max(c, scales, m):  # type: ignore[no-untyped-def]
    """max |c / scales| (NaN if any entry is NaN, as numpy's max)."""
    worst = 0.0
    for r in range(m):
        value = abs(c[r] / scales[r])
        if not value <= worst:
            worst = value
    return worst


@njit(cache=True, error_model="numpy")
def partitioned(  # type: ignore[no-untyped-def]
    level, t, y, out, ints, reals, lints, lreals, index, vec, jacs, mats, work, scratch, us
):  # fmt: skip
    """Up to `level` at (t, y), y = (q_I, q'_I, ...); with RATES, out <- (q'_I, q''_I, applied power,
    dissipation, driver power). Returns the status (OK, NOT_CONVERGED, SINGULAR) and the last scaled
    constraint residual. Long on purpose: one right-hand side is one compiled call, its steps
    (predictor, Newton, rates, the reduced solve) marked by comments as in the module's docstring."""
    ind, dep, sizes, piv, pt, rpiv, pa = (
        index[IND],
        index[DEP],
        index[SIZES],
        index[PIV],
        index[PIV_TRIAL],
        index[RPIV],
        index[PIV_ANCHOR],
    )
    n, m, f = sizes[S_N], sizes[S_M], sizes[S_F]
    lu, lt, reduced, x, tol = mats[LU], mats[LU_TRIAL], mats[REDUCED], mats[X], vec[TOL]
    q, qt, qd, zero = vec[Q, :n], vec[QT, :n], vec[QD, :n], vec[ZERO, :n]  # evaluate reads n from q
    ct, ct_last, move = vec[CT], vec[CT_LAST], vec[MOVE]
    jac, jt = jacs[LAST], jacs[TRIAL]
    c, q_d, scales = vec[C], vec[Q_D], vec[ROW_SCALE]
    qa, ja, la = vec[Q_ANCHOR, :n], jacs[ANCHOR], mats[LU_ANCHOR]
    for i in range(n):
        qt[i] = qa[i]
    if sizes[S_HAS_FACTORS]:  # tangent predictor
        c_t(ints, reals, t, ct)
        for r in range(m):
            s = 0.0
            for k in range(f):
                s += ja[r * n + ind[k]] * (y[k] - qa[ind[k]])
            move[r] = s + ct[r] - vec[CT_ANCHOR, r]
        lu_solve(la, m, pa, move)
        for k in range(m):
            qt[dep[k]] -= move[k]
    for k in range(f):
        qt[ind[k]] = y[k]
    previous, residual, converged = math.inf, math.inf, False
    chord = sizes[S_HAS_FACTORS] != 0 and sizes[S_CHORD] != 0  # the anchor's factors, while they contract
    for _ in range(sizes[S_NEWTON]):
        evaluate(ints, reals, qt, zero, t, c, q_d, jt, work, scratch, us)
        residual = _scaled_max(c, scales, m)
        stalled = residual < tol[1] and residual > 0.5 * previous
        chord = chord and residual <= CHORD_CONTRACTION * previous
        previous = residual
        if residual <= tol[0] or stalled or not chord:
            for r in range(m):
                for k in range(m):
                    lt[r, k] = jt[r * n + dep[k]]
            lu_factor(lt, m, pt)
        if residual <= tol[0] or stalled:
            converged = True
            break
        for r in range(m):
            move[r] = c[r]
        if chord:
            lu_solve(la, m, pa, move)
        else:
            lu_solve(lt, m, pt, move)
        for k in range(m):
            qt[dep[k]] -= move[k]
    if not converged:
        return NOT_CONVERGED, residual
    for i in range(n):
        q[i] = qt[i]
    for i in range(m * n):
        jac[i] = jt[i]
    for r in range(m):
        piv[r] = pt[r]
        for k in range(m):
            lu[r, k] = lt[r, k]
    c_t(ints, reals, t, ct_last)
    vec[TIMES, 0] = t
    if level == POSITIONS:
        return OK, residual

    for k in range(f):
        qd[ind[k]] = y[f + k]
    for r in range(m):
        s = -ct_last[r]
        for k in range(f):
            s -= jac[r * n + ind[k]] * qd[ind[k]]
        move[r] = s
    lu_solve(lu, m, piv, move)
    for k in range(m):
        qd[dep[k]] = move[k]

    evaluate(ints, reals, q, qd, t, c, q_d, jt[:0], work, scratch, us)
    loads(lints, lreals, vec[GRAVITY], q, qd, t, vec[QE, :n], work[POINTS:], vec[TOTALS])
    if _accelerations(n, m, f, ind, dep, jac, lu, piv, vec, reduced, rpiv, x):
        return SINGULAR, residual
    if level == STATE:
        return OK, residual

    totals, qdd, lam = vec[TOTALS], vec[QDD], vec[LAM]
    power = 0.0
    for r in range(sizes[S_DRIVERS], m):
        s = 0.0
        for j in range(n):
            s += jac[r * n + j] * qd[j]
        power -= lam[r] * s
    for k in range(f):
        out[k], out[f + k] = qd[ind[k]], qdd[ind[k]]
    out[2 * f], out[2 * f + 1], out[2 * f + 2] = totals[1], totals[2], power
    return OK, residual


@njit(cache=True, error_model="numpy")
def anchor(index, vec, jacs, mats):  # type: ignore[no-untyped-def]
    """The last converged q, C_t, C_q and LU of C_D become the start of the calls that follow."""
    n, m = index[SIZES, S_N], index[SIZES, S_M]
    for i in range(n):
        vec[Q_ANCHOR, i] = vec[Q, i]
    for r in range(m):
        vec[CT_ANCHOR, r] = vec[CT_LAST, r]
        index[PIV_ANCHOR, r] = index[PIV, r]
        for k in range(m):
            mats[LU_ANCHOR, r, k] = mats[LU, r, k]
    for i in range(m * n):
        jacs[ANCHOR, i] = jacs[LAST, i]
    index[SIZES, S_HAS_FACTORS] = 1


@njit(cache=True, error_model="numpy")
def _accelerations(n, m, f, ind, dep, jac, lu, piv, vec, reduced, rpiv, x):  # type: ignore[no-untyped-def]
    """vec[QDD], vec[LAM] <- q'' and lambda of M q'' + C_q^T lambda = Q_e, C_q q'' = Q_d, in the
    independent accelerations: with X = C_D^-1 C_I and p = C_D^-1 Q_d (C_D's LU is at hand),
    q''_D = p - X q''_I and (M_I + X^T M_D X) q''_I = Q_e,I - X^T (Q_e,D - M_D p); then
    C_D^T lambda = Q_e,D - M_D q''_D. True if the reduced mass matrix has an exactly zero pivot.
    reduced (f, f) and x (m, f) are scratch."""
    mass, qe, qdd, lam, p = vec[MASS], vec[QE], vec[QDD], vec[LAM], vec[RHS]
    for k in range(f):
        for r in range(m):
            p[r] = jac[r * n + ind[k]]
        lu_solve(lu, m, piv, p)
        for r in range(m):
            x[r, k] = p[r]
    for r in range(m):
        p[r] = vec[Q_D, r]
    lu_solve(lu, m, piv, p)
    for a in range(f):
        s = qe[ind[a]]
        for r in range(m):
            s -= x[r, a] * (qe[dep[r]] - mass[dep[r]] * p[r])
        qdd[ind[a]] = s
        for b in range(f):
            s = mass[ind[a]] if a == b else 0.0
            for r in range(m):
                s += mass[dep[r]] * x[r, a] * x[r, b]
            reduced[a, b] = s
    if lu_factor(reduced, f, rpiv):
        return True
    for a in range(f):
        lam[a] = qdd[ind[a]]
    lu_solve(reduced, f, rpiv, lam)
    for a in range(f):
        qdd[ind[a]] = lam[a]
    for r in range(m):
        s = p[r]
        for a in range(f):
            s -= x[r, a] * qdd[ind[a]]
        qdd[dep[r]] = s
    for r in range(m):
        lam[r] = qe[dep[r]] - mass[dep[r]] * qdd[dep[r]]
    lu_solve_transposed(lu, m, piv, lam)
    return False


@njit(cache=True, error_model="numpy")
def conditioning(jac, index, vec):  # type: ignore[no-untyped-def]
    """The reciprocal 2-norm condition number of the scaled dependent block B of `jac` (m, n), as
    Partitioned.conditioning: sqrt of the extreme eigenvalues of B^T B (accurate to round-off over
    its square, 1e-12 relative at a reciprocal condition number of 1e-2)."""
    dep, m = index[DEP], index[SIZES, S_M]
    block = np.empty((m, m))
    for r in range(m):
        for k in range(m):
            block[r, k] = jac[r, dep[k]] * vec[COL_SCALE, dep[k]] / vec[ROW_SCALE, r]
    values = np.linalg.eigvalsh(block.T @ block)
    return math.sqrt(max(values[0], 0.0) / values[-1])
