"""The kinematic time loop of reference_solver.analysis, compiled: assembly, predictor, Newton-Raphson,
halved-step approach, conditioning and determinant-sign checks, velocity and acceleration solves.

It decides nothing a diagnosis depends on: at the first abnormal event (assembly or Newton failure,
a reciprocal condition number below `threshold`, a determinant sign change) it stops and reports
the event and the time index, and the caller hands the run to the plain path.
`run` is the one compiled entry: the helpers are inlined into it (numba re-optimizes every callee
inside each caller, so a deep call tree would multiply the compile time), and every array is made
once, at its top (an array view made in a loop costs atomic reference counts). It marches the grid
points [start, stop) and can be called again from `stop`: compiled code never returns to the
interpreter, so the caller marches a long grid in chunks and a signal's handler runs between them.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from reference_solver.compiled.band import factor, norm1, norm_inf, rcond, solve
from reference_solver.compiled.evaluate import c_t, evaluate, profile_points
from reference_solver.compiled.program import S_BODIES, S_KL, S_KU, S_N, S_WIDTH, WIDTH
from reference_solver.limits import JUMP_FLOOR, JUMP_FRACTION

OK, ASSEMBLY_FAILED, NOT_CONVERGED, NEAR_SINGULAR, SIGN_CHANGE, UNVERIFIED, BRANCH_JUMP = range(7)
EVENTS = (
    "ok",
    "assembly failed",
    "Newton-Raphson failed",
    "near-singular C_q",
    "det C_q changed sign",
    "mobility not verified (C_q not clearly regular at the guess)",
    "a step left its branch (analysis.jumped)",
)
C, Q_D, ZERO, TMP, RHS, DX, EST, SIGNS, C_T, TRIAL, TRIAL2, PRED, ROWS = range(13)
"""Rows of run's scratch vectors `v`."""


@njit(cache=True, error_model="numpy", inline="always")
def _evaluate(ints, reals, profiles, splines, q, qd, t, c, q_d, lu, work, jac, us):  # type: ignore[no-untyped-def]
    """evaluate.evaluate after the cam profiles at q (an empty `lu`: no Jacobian)."""
    if profiles.shape[0]:
        profile_points(profiles, splines, q, (q.size - us.shape[0]) // 3, us)
    evaluate(ints, reals, q, qd, t, c, q_d, lu, work, jac, us)


@njit(cache=True, error_model="numpy", inline="always")
def _solve(lu, piv, perm, sizes, rhs, out, tmp):  # type: ignore[no-untyped-def]
    """out <- (scaled C_q)^-1 rhs, both in the original numbering."""
    n = rhs.size
    for i in range(n):
        tmp[i] = rhs[perm[0, i]]
    solve(lu, piv, n, sizes[S_KL], sizes[S_KU], sizes[S_WIDTH], tmp)
    for j in range(n):
        out[perm[1, j]] = tmp[j]


@njit(cache=True, error_model="numpy", inline="always")
def _scaled_max(c, scales):  # type: ignore[no-untyped-def]
    """max |C| in scaled units (NaN if any row is NaN)."""
    worst = 0.0
    for r in range(c.size):
        value = abs(c[r] / scales[0, r])
        if not value <= worst:
            worst = value
    return worst


@njit(cache=True, error_model="numpy", inline="always")
def _rates(  # type: ignore[no-untyped-def]
    ints, reals, profiles, splines, scales, perm, sizes, lu, piv, q, t, qd, qdd, v, work, jac, us, none
):  # fmt: skip
    """q_dot from C_q q_dot = -C_t, q_ddot from C_q q_ddot = Q_d, with the factors in `lu`; v are
    run's scratch vectors."""
    c, q_d, tmp, rhs, ct = v[C], v[Q_D], v[TMP], v[RHS], v[C_T]
    n = q.size
    c_t(ints, reals, t, ct)
    for r in range(n):
        rhs[r] = -ct[r] / scales[0, r]
    _solve(lu, piv, perm, sizes, rhs, qd, tmp)
    for i in range(n):
        qd[i] *= scales[1, i]
    _evaluate(ints, reals, profiles, splines, q, qd, t, c, q_d, none, work, jac, us)
    for r in range(n):
        rhs[r] = q_d[r] / scales[0, r]
    _solve(lu, piv, perm, sizes, rhs, qdd, tmp)
    for i in range(n):
        qdd[i] *= scales[1, i]


@njit(cache=True, error_model="numpy")
def run(  # type: ignore[no-untyped-def]
    ints, reals, scales, perm, sizes, parity, profiles, splines,
    grid, guess, tolerance, max_iterations, assembly_iterations, halvings, threshold, margin,
    q_all, qd_all, qdd_all, iterations, residual, rconds, start, stop, state,
):  # fmt: skip
    """The analysis over grid points [start, stop) into the output arrays; returns (event, time
    index), the index `stop` when every point was done.

    From start 0 it first verifies the mobility: sqrt(rcond_1 rcond_inf) of the scaled C_q at the
    guess, which bounds the 2-norm reciprocal condition number from below, must exceed `margin`;
    then it assembles at the guess. From a later start it continues from the point before, as
    stored in the output arrays, with that point's determinant sign in `state[0]` (written back on
    return). Long on purpose: its steps (assembly, Newton with backtracking, the rate solves) share
    the band factors in local arrays that a split would pass on every time point."""
    n, kl, ku, w = sizes[S_N], sizes[S_KL], sizes[S_KU], sizes[S_WIDTH]
    lu, piv, none, v = np.empty(n * w), np.empty(n, np.int64), np.empty(0), np.zeros((ROWS, n))
    c, q_d, zero, tmp, rhs, dx = v[C], v[Q_D], v[ZERO], v[TMP], v[RHS], v[DX]
    est, signs, trial, trial2, pred = v[EST], v[SIGNS], v[TRIAL], v[TRIAL2], v[PRED]
    work, jac = np.empty((5, max(sizes[S_BODIES], WIDTH))), np.empty((2, 2, WIDTH))
    us = np.empty((profiles.shape[0], 4, 2))
    q, qd, qdd = guess.copy(), np.zeros(n), np.zeros(n)
    previous = state[0]
    t0, t1, k = grid[0], grid[0], -1  # k = -1: the assembly, by damped Newton-Raphson from the guess
    if start > 0:  # continue from the point before
        k, t0, t1 = start, grid[start - 1], grid[start]
        for i in range(n):
            q[i], qd[i], qdd[i] = q_all[start - 1, i], qd_all[start - 1, i], qdd_all[start - 1, i]
    else:
        # ---- mobility ----
        _evaluate(ints, reals, profiles, splines, q, qd, 0.0, c, q_d, lu, work, jac, us)
        anorm, anorm_inf = norm1(lu, n, kl, ku, w, tmp), norm_inf(lu, n, kl, ku, w)
        at_guess = 0.0
        if factor(lu, piv, n, kl, ku, w) != 0.0:
            at_guess = rcond(lu, piv, n, kl, ku, w, anorm, est, signs, False)
            at_guess = math.sqrt(at_guess * rcond(lu, piv, n, kl, ku, w, anorm_inf, est, signs, True))
        if not at_guess > margin:
            return UNVERIFIED, 0

    while k < stop:
        # ---- advance (q, qd, qdd) from t0 to t1: Newton-Raphson from the predictor, and if that
        # fails, analysis._approach's halved steps (which also move qd and qdd) ----
        t, h, halving = t0, t1 - t0, False
        while True:
            target = t1 if not halving else (min(t + h, t1) if t1 > t0 else max(t + h, t1))
            for i in range(n):
                trial[i] = q[i] + (target - t) * qd[i] + 0.5 * (target - t) ** 2 * qdd[i]
                pred[i] = trial[i]
            # ---- reference_solver.newton on trial at target ----
            limit, damping = (assembly_iterations, halvings) if k < 0 else (max_iterations, 0)
            step, res, its, sign, anorm, converged = math.inf, 0.0, 0, 0.0, 0.0, False
            for its in range(limit + 1):
                _evaluate(ints, reals, profiles, splines, trial, zero, target, c, q_d, lu, work, jac, us)
                res = _scaled_max(c, scales)
                if not math.isfinite(res):
                    break
                converged = res < tolerance and step < tolerance
                if converged:  # the norm only where the condition number will be estimated
                    anorm = norm1(lu, n, kl, ku, w, tmp)
                sign = factor(lu, piv, n, kl, ku, w) * parity
                if converged:
                    break
                if its == limit or sign == 0.0:
                    break
                for r in range(n):
                    rhs[r] = -c[r] / scales[0, r]
                _solve(lu, piv, perm, sizes, rhs, dx, tmp)
                scale = 1.0
                for _ in range(damping):  # newton._backtrack: halve until the scaled residual drops
                    for i in range(n):
                        trial2[i] = trial[i] + scale * dx[i] * scales[1, i]
                    _evaluate(
                        ints, reals, profiles, splines, trial2, zero, target, c, q_d, none, work, jac, us
                    )
                    value = _scaled_max(c, scales)
                    if math.isfinite(value) and value < res:
                        break
                    scale *= 0.5
                step = 0.0
                for i in range(n):
                    trial[i] += scale * dx[i] * scales[1, i]
                    step = max(step, abs(scale * dx[i]))
            # ---- the step's outcome ----
            if converged and k > 0:  # analysis.jumped: the plain path retakes a step that left its branch
                correction, reach, dt = 0.0, 0.0, target - t
                for i in range(n):
                    correction = max(correction, abs(trial[i] - pred[i]) / scales[1, i])
                    reach = max(reach, (abs(dt * qd[i]) + dt * dt * abs(qdd[i])) / scales[1, i])
                if correction > max(JUMP_FRACTION * reach, JUMP_FLOOR):
                    return BRANCH_JUMP, k
            if converged and halving:
                rc = rcond(lu, piv, n, kl, ku, w, anorm, est, signs, False) if sign != 0.0 else 0.0
                if rc < threshold:
                    return NEAR_SINGULAR, k
            if converged:
                for i in range(n):
                    q[i] = trial[i]
                t = target
                if t == t1:
                    break
                # fmt: off
                _rates(ints, reals, profiles, splines, scales, perm, sizes, lu, piv, q, t, qd, qdd,
                       v, work, jac, us, none)
                # fmt: on
                h *= 2
            elif k < 0:
                return ASSEMBLY_FAILED, 0
            elif halving:
                h /= 2
            else:
                halving, h = True, (t1 - t0) / 2
            if halving and not abs(h) > 1e-12 * max(abs(t1), abs(t1 - t0)):
                return NOT_CONVERGED, k
        # ---- the checks and the rates at grid point k ----
        if k >= 0:
            iterations[k], residual[k] = its if k > 0 else 0, res
            rc = rcond(lu, piv, n, kl, ku, w, anorm, est, signs, False) if sign != 0.0 else 0.0
            if rc < threshold:
                return NEAR_SINGULAR, k
            if k > 0 and sign != previous:
                return SIGN_CHANGE, k
            previous = sign
            # fmt: off
            _rates(ints, reals, profiles, splines, scales, perm, sizes, lu, piv, q, t1, qd, qdd,
                   v, work, jac, us, none)
            # fmt: on
            for i in range(n):
                q_all[k, i], qd_all[k, i], qdd_all[k, i] = q[i], qd[i], qdd[i]
            rconds[k] = rc
        k += 1
        if k < stop:
            t0, t1 = grid[max(k - 1, 0)], grid[k]
    state[0] = previous
    return OK, stop
