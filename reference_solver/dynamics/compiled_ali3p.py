"""ALI3-P with its time steps in one compiled call (compiled.ali3p_kernel): the same method as Ali3p over
the compiled constraint rows, for scenarios without force elements, so W = M + h^2/4 C_q^T alpha C_q
is symmetric positive definite and banded Cholesky factors it. `ali3p_stepper` gives it where the
constraints compile, Ali3p otherwise; Ali3p stays the plain reference each is checked against.
Compiled, so that A02 as specified (1e6 steps of 243 coordinates) runs in minutes; its figures are
held by tests/reference_solver/dynamics/test_ali3p.py."""

from __future__ import annotations

from types import ModuleType

import numpy as np

from reference_solver.compiled import ali3p_kernels
from reference_solver.compiled.constraint_rows import NotCompiled
from reference_solver.compiled.program import K_SLOT_COL, WIDTH, compile_dense
from reference_solver.compiled_system import CompiledSystem
from reference_solver.dynamics.ali3p import PENALTY, Ali3p, StepState
from reference_solver.dynamics.loads import Loads
from reference_solver.errors import ConvergenceError
from reference_solver.system import ConstraintSystem


class CompiledAli3p(Ali3p):
    """Ali3p whose steps run in compiled.ali3p_kernel.advance (`kernels`); its state lives in `vec`."""

    def __init__(
        self, system: CompiledSystem, mass: np.ndarray, loads: Loads, h: float, kernels: ModuleType
    ) -> None:
        if system.scenario.forces:
            raise NotCompiled("ALI3-P's compiled step takes no force elements (W would not be symmetric)")
        super().__init__(system, mass, loads, h)
        k = self.kernels = kernels
        program = compile_dense(system, by_rows=True)
        n, m = system.unknowns, system.size
        self.n, self.m = n, m
        columns = program.ints[:, K_SLOT_COL : K_SLOT_COL + WIDTH]
        width = max(
            (int(np.ptp(row[row >= 0])) for row in columns if np.any(row >= 0)),
            default=0,
        )
        self.vec = np.zeros((k.VECTORS, max(n, m)))
        self.vec[k.MASS, :n] = mass
        self.vec[k.QE, :n] = loads.gravity  # no force elements: Q_e is gravity, constant
        self.vec[k.COL_SCALE, :n], self.vec[k.ROW_SCALE, :m] = system.column_scales, system.row_scales
        self.sizes = np.zeros(8, np.int64)
        self.sizes[[k.S_N, k.S_M, k.S_W]] = n, m, width
        self.sizes[k.S_DRIVERS] = int(system.offsets[len(system.scenario.joints)])
        self.params = np.zeros(6)
        self.params[k.P_H], self.params[k.P_PENALTY] = h, PENALTY
        self.band = np.zeros((n, width + 1))
        self.arguments = (
            *(program.ints, program.reals, self.vec, self.sizes, self.params, np.zeros(m * WIDTH)),
            *(self.band, np.zeros((m, m)), np.zeros(m, np.int64)),
            *(
                np.zeros((5, max(len(system.layout.bodies), WIDTH))),
                np.zeros((2, 2, WIDTH)),
                np.zeros((0, 4, 2)),
            ),
        )

    @property
    def slow_steps(self) -> int:
        """How many times a step or projection finished through the Schur complement."""
        return int(self.sizes[self.kernels.S_SLOW])

    def run(
        self, s: StepState, count: int, power: np.ndarray, work: np.ndarray
    ) -> tuple[StepState, np.ndarray, np.ndarray]:
        """`count` steps from s, with the powers (applied, dissipated, drivers) at s and the work
        integrals so far; returns the state and both at the end (no force elements: the first two
        stay zero)."""
        k, n, m, vec = self.kernels, self.n, self.m, self.vec
        vec[k.Q, :n], vec[k.QD, :n], vec[k.QDD, :n], vec[k.LAM, :m] = s.q, s.qd, s.qdd, s.multipliers
        self.params[k.P_T], self.params[k.P_WORK], self.params[k.P_POWER] = s.t, 0.0, power[2]
        before = self.sizes[k.S_EVALUATIONS]
        status = k.advance(count, *self.arguments)
        self.evaluations += int(self.sizes[k.S_EVALUATIONS] - before)
        t = float(self.params[k.P_T])
        self.alpha = vec[k.ALPHA, :m].copy()
        if status == k.NOT_POSITIVE:
            raise np.linalg.LinAlgError("ALI3-P's iteration matrix is not positive definite")
        if status != k.OK:  # t is the failed step's start
            end = t + float(self.params[k.P_H])
            what = {
                k.SINGULAR: "ALI3-P's Schur complement C_q W^-1 C_q^T is singular (C_q lost rank)",
                k.NOT_PROJECTED: "ALI3-P's projection of the rates gave non-finite rates",
            }.get(status, "ALI3-P's Newton iteration did not converge")
            raise ConvergenceError(
                f"{self.system.scenario.name}: {what} at t={end:.6g}", time=end, q=vec[k.Q, :n].copy()
            )
        q = vec[k.Q, :n].copy()
        state = StepState(
            t,
            q,
            vec[k.QD, :n].copy(),
            vec[k.QDD, :n].copy(),
            vec[k.LAM, :m].copy(),
            self.system.jacobian(q, t),
            int(self.sizes[k.S_ITERATIONS]),
        )
        now = np.array([0.0, 0.0, self.params[k.P_POWER]])
        return state, now, work + np.array([0.0, 0.0, self.params[k.P_WORK]])

    def step(self, s: StepState) -> StepState:
        return self.run(s, 1, np.zeros(3), np.zeros(3))[0]

    @property
    def careful(self) -> bool:
        """Whether Newton and the projections go through the Schur complement from their first
        iteration (next to a singular passage, dynamics.passage)."""
        return bool(self.params[self.kernels.P_CAREFUL])

    @careful.setter
    def careful(self, value: bool) -> None:
        self.params[self.kernels.P_CAREFUL] = float(value)

    def run_length(
        self, s: StepState, length: float, power: np.ndarray, work: np.ndarray
    ) -> tuple[StepState, np.ndarray, np.ndarray]:
        """One step of `length` instead of h (a step placed around a singular passage); the
        penalties stay those of h."""
        self.params[self.kernels.P_H] = length
        try:
            return self.run(s, 1, power, work)
        finally:
            self.params[self.kernels.P_H] = self.h

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        """W^-1 rhs with the last step's factors."""
        x = np.array(rhs, dtype=float)
        self.kernels.solve(self.band, self.n, int(self.sizes[self.kernels.S_W]), x)
        return x


def ali3p_stepper(system: ConstraintSystem, mass: np.ndarray, loads: Loads, h: float) -> Ali3p:
    """CompiledAli3p where the system is compiled and has no force elements, else Ali3p."""
    if isinstance(system, CompiledSystem) and not system.scenario.forces:
        kernels, _ = ali3p_kernels()
        if kernels is not None:
            try:
                return CompiledAli3p(system, mass, loads, h, kernels)
            except NotCompiled:
                pass
    return Ali3p(system, mass, loads, h)
