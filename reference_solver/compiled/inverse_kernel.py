"""Inverse dynamics over a trajectory (or a chunk of it) in one numba call: at each time C_q from
the compiled rows (compiled.evaluate), Q_e from the compiled loads (compiled.load_kernel), and the
multipliers from the first block row of the augmented equations, C_q^T lambda = Q_e - M q'', in the
least-squares sense (LAPACK's gelsd, as scipy's lstsq in reference_solver.dynamics.inverse, the
plain path it is checked against). The reactions need only each joint's rows of C_q at its first
moving body's x and y, so those products with lambda are returned instead of C_q at every time."""

from __future__ import annotations

import numpy as np
from numba import njit

from reference_solver.compiled.evaluate import evaluate
from reference_solver.compiled.load_kernel import loads


@njit(cache=True, error_model="numpy")
def multipliers(  # type: ignore[no-untyped-def]
    ints, reals, lints, lreals, gravity, mass, times, q, qd, qdd, first, lam, pairs, potential, work, jac
):  # fmt: skip
    """For each time k: lam[k] <- lambda, pairs[k, r] <- C_q[r, first[r]:first[r] + 2] lambda[r]
    (zero where first[r] < 0), potential[k] <- the loads' potential energy. `work` (5, width) and
    `jac` (2, 2, width) are the rows' scratch (compiled.evaluate)."""
    m, n = lam.shape[1], q.shape[1]
    c, q_d, store = np.empty(m), np.empty(m), np.empty(m * n)
    qe, points, totals, us = np.empty(n), np.zeros((2, 6)), np.zeros(3), np.zeros((0, 4, 2))
    transposed = np.empty((n, m))
    rhs = np.empty(n)
    for k in range(times.size):
        evaluate(ints, reals, q[k], qd[k], times[k], c, q_d, store, work, jac, us)
        loads(lints, lreals, gravity, q[k], qd[k], times[k], qe, points, totals)
        for r in range(m):
            for i in range(n):
                transposed[i, r] = store[r * n + i]
        for i in range(n):
            rhs[i] = qe[i] - mass[i] * qdd[k, i]
        solution = np.linalg.lstsq(transposed, rhs)[0]
        for r in range(m):
            lam[k, r] = solution[r]
            col = first[r]
            if col >= 0:
                pairs[k, r, 0] = store[r * n + col] * solution[r]
                pairs[k, r, 1] = store[r * n + col + 1] * solution[r]
            else:
                pairs[k, r, 0], pairs[k, r, 1] = 0.0, 0.0
        potential[k] = totals[0]
