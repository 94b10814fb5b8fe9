"""The compiled path's kernels for a constraint system that is not square: C, the dense C_q, Q_d and
C_t at one state, as forward dynamics asks for them at every right-hand side (program.compile_dense
places the Jacobian in a row-major dense store)."""

from __future__ import annotations

import numpy as np
from numba import njit

from reference_solver.compiled.evaluate import evaluate, row_motion
from reference_solver.compiled.program import WIDTH, Program


@njit(cache=True, error_model="numpy")
def rates_of_time(ints, reals, t, out):  # type: ignore[no-untyped-def]
    """out <- C_t(t): minus the motion's rate on each driven row (C = ... - f(t))."""
    for r in range(ints.shape[0]):
        _, df, _ = row_motion(ints, reals, r, t)
        out[r] = -df


class DenseKernels:
    """One program's evaluation with its scratch arrays kept (no cam contacts: no profile points)."""

    def __init__(self, program: Program) -> None:
        self.program, self.rows, self.columns = program, program.ints.shape[0], program.n
        bodies = int(program.sizes[1])
        self.work = np.zeros((5, max(bodies, WIDTH)))
        self.scratch = np.zeros((2, 2, WIDTH))
        self.points = np.zeros((0, 4, 2))

    def evaluate(self, q: np.ndarray, qd: np.ndarray, t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """C, the dense C_q and Q_d at (q, qd, t)."""
        c, q_d = np.empty(self.rows), np.empty(self.rows)
        store = np.empty(self.rows * self.columns)
        p = self.program
        evaluate(p.ints, p.reals, q, qd, float(t), c, q_d, store, self.work, self.scratch, self.points)
        return c, store.reshape(self.rows, self.columns), q_d

    def c_t(self, t: float) -> np.ndarray:
        out = np.empty(self.rows)
        rates_of_time(self.program.ints, self.program.reals, float(t), out)
        return out
