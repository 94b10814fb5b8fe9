"""ALI3-P's time steps (reference_solver.dynamics.ali3p) in numba, for scenarios without force
elements (P = M, so W = M + h^2/4 C_q^T diag(alpha) C_q is symmetric positive definite): the compiled
constraint rows (compiled.evaluate, C_q stored row by row, program.RowStore), W's banded Cholesky
factors, the Newton iteration with multiplier updates and the projections of the rates.

Where the augmented Lagrangian contracts slowly (a step ending next to a singular configuration: it
contracts by 1/(1 + PENALTY s^2) along a direction whose scaled singular value s vanishes there), the
plain path stops at a stalled update, leaving the rockers of A02 off the crank by up to 8e-9 rad.
Here Newton then continues on positions and multipliers together, through the Schur complement
S = h^2/4 C_q W^-1 C_q^T (dense, factored by compiled.dense_lu), to the round-off of C divided by s,
and the projections finish the same way. Near an A02 passage that is not enough: the augmented
Lagrangian's small updates there are taken for convergence with the rockers up to 1e-10 off the
crank, and a step ending next to the instant leaves them C's round-off over s off. So the grid
(dynamics.ali3p_schedule, dynamics.passage) sets P_CAREFUL there, which sends Newton and the
projections through the Schur complement from their first iteration, and places its steps so that
none ends within half a step of the instant.

The trapezoidal rates are formed from the step's increment, q' = 2/h (q - q_n) - q'_n and
q'' = 4/h^2 (q - q_n) - 4/h q'_n - q''_n, not from q itself as dynamics.ali3p writes them
(2/h q + qhat'_n): on A02, whose coordinates reach 40 m, that form gives q'' the round-off of
4/h^2 40 eps (1e-4 rad/s^2 at h = 2e-5), and the energy a drift that grew as h shrank.

Arrays come in as in compiled.rates: rows of `vec` are the vectors named below, `sizes` the integers.
"""

from __future__ import annotations

import math

from numba import njit

from reference_solver.compiled.ali3p_matrix import factor, jac_t_times, jac_times, solve
from reference_solver.compiled.dense_lu import lu_factor, lu_solve
from reference_solver.compiled.evaluate import c_t, evaluate
from reference_solver.compiled.program import K_SLOT_COL, K_WIDTH, WIDTH

(Q, QD, QDD, LAM, MASS, QE, COL_SCALE, ROW_SCALE, ALPHA) = range(9)
(STEP, HAT_A, C, Q_D, RES, PUSH, GAP, TARGET, GIVEN, KKT, DMU, COLUMN, IMAGE, ZERO) = range(9, 23)
VECTORS = 23
"""Rows of `vec`, each max(n, m) long: the state (Q, QD, QDD, the multipliers LAM), the constants
(MASS, QE the constant generalized loads, the column and row scales, ALPHA the penalties, set at
the first factorization), then scratch."""
S_N, S_M, S_W, S_DRIVERS, S_EVALUATIONS, S_SLOW, S_ITERATIONS = range(7)
"""Entries of `sizes`: coordinates, rows, W's half-bandwidth, first driver row; counters of
constraint evaluations and slow (Schur) factorizations, and the last step's Newton iterations."""
P_H, P_T, P_PENALTY, P_WORK, P_POWER, P_CAREFUL = range(6)
"""Entries of `params`: the step, the time, the penalty (dynamics.ali3p.PENALTY), the drivers' work,
the last state's driver power, and whether the steps are careful (nonzero: Newton and the projections
go through the Schur complement from their first iteration, as next to a singular passage, where the
augmented Lagrangian barely moves the directions C_q is losing; dynamics.passage)."""
OK, NOT_CONVERGED, NOT_POSITIVE, SINGULAR, NOT_PROJECTED = 0, 1, 2, 3, 4
"""`advance`'s status: a step done; Newton not converged; W not positive definite; the Schur
complement exactly singular (an exactly zero pivot: C_q lost rank); a projection of the rates that
gave non-finite rates (a non-finite target, such as a driver's acceleration that overflows)."""
NEWTON_STEPS = 60
TOLERANCE = 1e-13
"""As in dynamics.ali3p: the scaled constraint residual and update Newton must reach."""
SLOW = 0.9
STALLED = 1e-9
EPSILON = 2.220446049250313e-16
"""A Newton update that shrinks by less than SLOW has stalled. Above the round-off floor, the
augmented Lagrangian is slow: Newton continues through the Schur complement. Below it, or once
through it, the stall is round-off, and Newton stops there if the update is below STALLED and C
holds, as dynamics.ali3p does. The floor: the penalty times C's round-off, pushed along a direction
of small s, moves q by up to PENALTY^(1/2) times that round-off / 2 (scaled). compiled.evaluate sums
positions apart from rotated vectors, so C's round-off is that of link-sized quantities, EPSILON
in scaled units, whatever the coordinates' size. The floor was EPSILON max|q| (scaled) while C lost
the coordinates' round-off to cancellation: 9e-11 on A02's 40 m chain, above which a slow augmented
Lagrangian was taken for round-off and its iterate kept, the rockers off the crank by up to 3e-9
where a step ends next to a passage (measured: 2 loops moved 1 to 40 m along x, 3.4e-9 against
6e-12 now). Measured on A02's first 1.5 s at h = 3e-5 (40 loops, 50000 steps): the Schur
complement at 15 steps (198 with no floor, 5 with the old one), rockers within 1.5e-11 of the crank
(8e-10 before)."""
SLOW_START = 0.01
"""A projection is slow where no move before its stall shrank by this factor (1 + PENALTY s^2 <
1 / SLOW_START)."""
PROJECTION_STEPS = 30
SETTLED = 1e-15
PROJECTION_STALLED = 1e-13
"""A projection stops at a move below SETTLED (relative to the rates' largest), or below
PROJECTION_STALLED when no longer halving (dynamics.projection); a slow one (see _project)
finishes through the Schur complement."""


@njit(cache=True, error_model="numpy")
def _schur(ints, store, vec, sizes, band, weight, schur, pivots):  # type: ignore[no-untyped-def]
    """schur <- the LU factors of S = weight C_q W^-1 C_q^T (dense). False if S is exactly singular
    (a zero pivot: its factors would divide by zero)."""
    n, m, w = sizes[S_N], sizes[S_M], sizes[S_W]
    column, image = vec[COLUMN], vec[IMAGE]
    for r in range(m):
        for i in range(n):
            column[i] = 0.0
        for k in range(ints[r, K_WIDTH]):
            col = ints[r, K_SLOT_COL + k]
            if col >= 0:
                column[col] += weight * store[r * WIDTH + k]
        solve(band, n, w, column)
        jac_times(ints, store, m, column, image)
        for i in range(m):
            schur[i, r] = image[i]
    sizes[S_SLOW] += 1
    return not lu_factor(schur, m, pivots)


@njit(cache=True, error_model="numpy")
def _kkt_correction(ints, store, vec, sizes, band, weight, schur, pivots, move, gap, multiplier):  # type: ignore[no-untyped-def]
    """With move = W^-1 f on entry: the Newton correction of [W, weight C_q^T; C_q, 0] [dx; dmu] =
    -[f; gap]. move <- -dx, multiplier += dmu."""
    n, m, w = sizes[S_N], sizes[S_M], sizes[S_W]
    dmu, pushed = vec[DMU], vec[PUSH]
    jac_times(ints, store, m, move, dmu)
    for r in range(m):
        dmu[r] = gap[r] - dmu[r]
    lu_solve(schur, m, pivots, dmu)
    jac_t_times(ints, store, m, n, dmu, pushed)
    for i in range(n):
        pushed[i] *= weight
    solve(band, n, w, pushed)
    for i in range(n):
        move[i] += pushed[i]
    for r in range(m):
        multiplier[r] += dmu[r]


@njit(cache=True, error_model="numpy")
def _project(ints, store, vec, sizes, band, weight, schur, pivots, rates, target, slow):  # type: ignore[no-untyped-def]
    """rates <- their M-orthogonal projection onto C_q x = target: the augmented Lagrangian iteration
    of dynamics.projection, through the Schur complement where Newton went through it (`slow`: S
    factored next to this C_q). Where Newton did not and the projection is slow (stalled, no move
    before it shrinking by SLOW_START), it stops as the positions did, short of the directions C_q
    is losing: an exact projection there, from positions held only by the augmented Lagrangian,
    set the rockers of a two-loop A02 off the crank by 1e-8 rad, this by 3e-9. False if a move is
    not finite (the largest move is a max(), which skips NaN: a NaN move would read as settled)."""
    n, m, w = sizes[S_N], sizes[S_M], sizes[S_W]
    mass, alpha, move, gap = vec[MASS], vec[ALPHA], vec[RES], vec[GAP]
    given, kkt = vec[GIVEN], vec[KKT]
    scale = 1e-300
    for i in range(n):
        given[i] = rates[i]
        scale = max(scale, abs(rates[i]))
    for r in range(m):
        kkt[r] = 0.0
    jac_times(ints, store, m, rates, gap)
    for r in range(m):
        gap[r] -= target[r]
    previous, best = math.inf, math.inf
    for _ in range(PROJECTION_STEPS):
        for r in range(m):
            gap[r] = alpha[r] * gap[r] + kkt[r]
        jac_t_times(ints, store, m, n, gap, move)
        for i in range(n):
            move[i] = mass[i] * (rates[i] - given[i]) + weight * move[i]
        solve(band, n, w, move)
        if slow:
            jac_times(ints, store, m, rates, gap)
            for r in range(m):
                gap[r] -= target[r]
            _kkt_correction(ints, store, vec, sizes, band, weight, schur, pivots, move, gap, kkt)
        size, finite = 0.0, True
        for i in range(n):
            rates[i] -= move[i]
            size = max(size, abs(move[i]))
            finite = finite and math.isfinite(move[i])
        if not finite:
            return False
        size /= scale
        jac_times(ints, store, m, rates, gap)
        for r in range(m):
            gap[r] -= target[r]
            if not slow:
                kkt[r] += alpha[r] * gap[r]
        if size <= SETTLED:
            return True
        if size > 0.5 * previous and (slow or size < PROJECTION_STALLED or best >= SLOW_START):
            return True  # stalled: round-off, or slow where Newton was not (see above)
        if previous < math.inf:
            best = min(best, size / previous)
        previous = size
    return True


@njit(cache=True, error_model="numpy")
def _penalties(ints, store, vec, sizes, params):  # type: ignore[no-untyped-def]
    """alpha_i = PENALTY 4/h^2 / (C_q M^-1 C_q^T)_ii, as dynamics.ali3p (at the first factorization)."""
    m, mass, alpha, h = sizes[S_M], vec[MASS], vec[ALPHA], params[P_H]
    typical = 0.0
    for r in range(m):
        s = 0.0
        for k in range(ints[r, K_WIDTH]):
            col = ints[r, K_SLOT_COL + k]
            if col >= 0:
                s += store[r * WIDTH + k] ** 2 / mass[col]
        alpha[r] = s
        typical = max(typical, s)
    if typical == 0.0:
        typical = 1.0
    for r in range(m):
        alpha[r] = params[P_PENALTY] * 4.0 / (h * h) / max(alpha[r], 1e-12 * typical)


@njit(cache=True, error_model="numpy")
def advance(count, ints, reals, vec, sizes, params, store, band, schur, pivots, work, scratch, us):  # type: ignore[no-untyped-def]
    """`count` ALI3-P steps from the state in vec (Q, QD, QDD, LAM) at params[P_T], in place, the
    drivers' work accumulated by the trapezoidal rule. Returns OK, or at the first step that fails
    NOT_CONVERGED (the state is then Newton's last iterate), NOT_POSITIVE, SINGULAR or NOT_PROJECTED
    (params[P_T] is then that step's start). Long on purpose: the step of dynamics.ali3p, its parts
    (predictor, Newton, projections, power) marked by comments."""
    n, m, w = sizes[S_N], sizes[S_M], sizes[S_W]
    h = params[P_H]
    weight = h * h / 4.0
    q, qd, qdd, lam, mass, qe = vec[Q], vec[QD], vec[QDD], vec[LAM], vec[MASS], vec[QE]
    step, hat_a, c, q_d, res, push = vec[STEP], vec[HAT_A], vec[C], vec[Q_D], vec[RES], vec[PUSH]
    alpha, cols, rows, zero, target = vec[ALPHA], vec[COL_SCALE], vec[ROW_SCALE], vec[ZERO], vec[TARGET]
    for _ in range(count):
        t = params[P_T] + h
        for i in range(n):  # predictor
            step[i] = h * qd[i] + h * h / 2.0 * qdd[i]
            hat_a[i] = -(4.0 / h * qd[i] + qdd[i])
            q[i] += step[i]
        slow, converged, previous = False, False, math.inf
        floor = math.sqrt(params[P_PENALTY]) * EPSILON
        for iteration in range(1, NEWTON_STEPS + 1):  # Newton, then Newton through S where slow
            evaluate(ints, reals, q, zero, t, c, q_d, store, work, scratch, us)
            sizes[S_EVALUATIONS] += 1
            if iteration == 1:
                if alpha[0] == 0.0:
                    _penalties(ints, store, vec, sizes, params)
                if not factor(ints, store, vec[MASS], vec[ALPHA], n, m, w, band, weight):
                    return NOT_POSITIVE
                if params[P_CAREFUL] != 0.0:
                    if not _schur(ints, store, vec, sizes, band, weight, schur, pivots):
                        return SINGULAR
                    slow = True
            elif not slow:
                for r in range(m):
                    lam[r] += alpha[r] * c[r]
            for r in range(m):
                push[r] = alpha[r] * c[r] + lam[r]
            jac_t_times(ints, store, m, n, push, res)
            for i in range(n):
                res[i] = weight * (mass[i] * (4.0 / (h * h) * step[i] + hat_a[i]) + res[i] - qe[i])
            solve(band, n, w, res)
            if slow:
                _kkt_correction(ints, store, vec, sizes, band, weight, schur, pivots, res, c, lam)
            size, violation, finite = 0.0, 0.0, True
            for i in range(n):
                q[i] -= res[i]
                step[i] -= res[i]
                size = max(size, abs(res[i] / cols[i]))
                finite = finite and math.isfinite(res[i])
            for r in range(m):
                violation = max(violation, abs(c[r] / rows[r]))
            sizes[S_ITERATIONS] = iteration
            if not finite:  # overflowed (a non-finite C gives a non-finite update): max() skips NaN
                return NOT_CONVERGED
            if violation <= TOLERANCE and size <= TOLERANCE:
                converged = True
                break
            if iteration >= 2:
                ratio = size / previous
                if ratio > SLOW:  # stalled: round-off, or a slow augmented Lagrangian
                    if slow or size < floor:
                        if size < STALLED and violation <= TOLERANCE:
                            converged = True
                            break
                    elif not _schur(ints, store, vec, sizes, band, weight, schur, pivots):
                        return SINGULAR
                    else:
                        slow = True
            previous = size
        if not converged:
            return NOT_CONVERGED
        evaluate(ints, reals, q, zero, t, c, q_d, store, work, scratch, us)  # projections
        for i in range(n):
            qd[i] = 2.0 / h * step[i] - qd[i]
            qdd[i] = 4.0 / (h * h) * step[i] + hat_a[i]
        c_t(ints, reals, t, target)
        for r in range(m):
            target[r] = -target[r]
        if not _project(ints, store, vec, sizes, band, weight, schur, pivots, qd, target, slow):
            return NOT_PROJECTED
        evaluate(ints, reals, q, qd, t, c, target, store[:0], work, scratch, us)
        if not _project(ints, store, vec, sizes, band, weight, schur, pivots, qdd, target, slow):
            return NOT_PROJECTED
        params[P_T] = t
        jac_times(ints, store, m, qd, push)  # the drivers' power, -lambda* . C_q q' over their rows
        power = 0.0
        for r in range(sizes[S_DRIVERS], m):
            power -= lam[r] * push[r]
        params[P_WORK] += h / 2.0 * (params[P_POWER] + power)
        params[P_POWER] = power
    return OK
