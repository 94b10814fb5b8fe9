"""The constraint residual of a whole trajectory in one compiled call: at each time, the cam profiles
at q (evaluate.profile_points), C(q, t) from the row instructions (evaluate.evaluate, no Jacobian),
and the largest scaled |C| over the rows that count (reference_solver.residual says which)."""

from __future__ import annotations

import numpy as np
from numba import njit

from reference_solver.compiled.evaluate import evaluate, profile_points
from reference_solver.compiled.program import WIDTH, Program


@njit(cache=True, error_model="numpy")
def residuals(ints, reals, profiles, splines, qs, times, row_scales, counted, out, work, scratch, points):  # type: ignore[no-untyped-def]
    """out[k] <- max |C(qs[k], times[k])[r]| / row_scales[r] over the rows r in `counted`, for every
    time k (NaN where a counted row is NaN). points (contacts, 4, 2) is the profile points'
    scratch, work and scratch evaluate's."""
    rows, n = ints.shape[0], qs.shape[1]
    c, q_d, q, qd, band = np.empty(rows), np.empty(rows), np.empty(n), np.zeros(n), np.empty(0)
    bodies = (n - points.shape[0]) // 3
    for k in range(times.size):
        for j in range(n):  # a copy, not a view: a view made in a loop costs atomic reference counts
            q[j] = qs[k, j]
        if profiles.shape[0]:
            profile_points(profiles, splines, q, bodies, points)
        evaluate(ints, reals, q, qd, times[k], c, q_d, band, work, scratch, points)
        worst = 0.0
        for r in counted:
            value = abs(c[r] / row_scales[r])
            if np.isnan(value):  # a row that cannot be evaluated is no closed loop: NaN, not skipped
                worst = np.nan
                break
            worst = max(worst, value)
        out[k] = worst


def trajectory_residuals(
    program: Program, qs: np.ndarray, times: np.ndarray, row_scales: np.ndarray, counted: np.ndarray
) -> np.ndarray:
    """The largest scaled |C| over the `counted` rows at each (qs[k], times[k]) (`residuals`), in
    scratch of its own: a program kept for many trajectories may be asked from more than one thread."""
    out = np.empty(len(times))
    qs = np.ascontiguousarray(qs, dtype=float)
    times = np.ascontiguousarray(times, dtype=float)
    work = np.zeros((5, max(int(program.sizes[1]), WIDTH)))
    scratch, points = np.zeros((2, 2, WIDTH)), np.zeros((program.profiles.shape[0], 4, 2))
    residuals(
        program.ints,
        program.reals,
        program.profiles,
        program.splines,
        qs,
        times,
        np.ascontiguousarray(row_scales, dtype=float),
        np.ascontiguousarray(counted, dtype=np.int64),
        out,
        work,
        scratch,
        points,
    )
    return out
