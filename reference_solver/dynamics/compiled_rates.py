"""The coordinate-partitioned ODE with its right-hand side in one compiled call (compiled.rates): the
same positions, rates and state as Partitioned, over the compiled constraint rows and force
elements, with no Python between them. `partitioned_ode` gives it where the constraints are compiled
(reference_solver.compiled_system) and every force element has a kernel, Partitioned otherwise."""

from __future__ import annotations

import math
from types import ModuleType

import numpy as np

from reference_solver.compiled import rates_kernels
from reference_solver.compiled.constraint_rows import NotCompiled
from reference_solver.compiled.load_program import compile_loads
from reference_solver.compiled.program import WIDTH
from reference_solver.compiled_system import CompiledSystem
from reference_solver.dynamics.loads import Loads, LoadState
from reference_solver.dynamics.partition import NEWTON_STEPS, RESIDUAL, STALLED, Partitioned, State
from reference_solver.errors import ConvergenceError
from reference_solver.system import ConstraintSystem

RETRY_STALLED = 1e-10
"""Where a retried Newton may stop when an iteration no longer halves the residual (round-off of
the compiled rows, which can sit a few times above STALLED)."""


class CompiledPartitioned(Partitioned):
    """Partitioned, its positions, state and rates evaluated by compiled.rates.partitioned (`kernels`)."""

    def __init__(
        self,
        system: CompiledSystem,
        mass: np.ndarray,
        loads: Loads,
        q: np.ndarray,
        independent: np.ndarray,
        kernels: ModuleType,
    ) -> None:
        super().__init__(system, mass, loads, q, independent)
        k = self.kernels = kernels
        program, forces = system.kernels.program, compile_loads(loads.forces, system.layout, loads.gravity)
        n, m, f = system.unknowns, system.size, independent.size
        self.n, self.m = n, m
        self.vec = np.zeros((k.VECTORS, n + m))
        self.vec[k.GRAVITY, :n], self.vec[k.MASS, :n] = forces.gravity, mass
        self.vec[k.ROW_SCALE, :m], self.vec[k.COL_SCALE, :n] = system.row_scales, system.column_scales
        self.vec[k.TOL, :2] = RESIDUAL, STALLED
        self.index = np.zeros((k.INDICES, max(n, m, 7)), np.int64)
        self.index[k.IND, :f], self.index[k.DEP, :m] = self.independent, self.dependent
        drivers = int(system.offsets[len(system.scenario.joints)])
        sizes = [k.S_N, k.S_M, k.S_F, k.S_DRIVERS, k.S_NEWTON, k.S_CHORD]
        self.index[k.SIZES, sizes] = n, m, f, drivers, NEWTON_STEPS, 1
        self.jacs = np.zeros((k.JACOBIANS, m * n))
        side, width = max(m, f), max(len(system.layout.bodies), WIDTH)
        self.matrices, work = np.zeros((k.MATRICES, side, side)), np.zeros((k.POINTS + 2, width))
        self.arguments = (
            *(program.ints, program.reals, forces.ints, forces.reals, self.index, self.vec, self.jacs),
            *(self.matrices, work, np.zeros((2, 2, WIDTH)), np.zeros((0, 4, 2))),
        )
        self.nothing = np.zeros(0)
        self.partitioned, self.outputs, self.level, self.ok = k.partitioned, 2 * f + 3, k.RATES, k.OK
        self.restart(q)

    def restart(self, q: np.ndarray) -> None:
        k = self.kernels
        self.vec[k.Q, : self.n] = self.vec[k.Q_ANCHOR, : self.n] = q
        self.vec[k.TIMES, 0] = math.nan
        self.index[k.SIZES, k.S_HAS_FACTORS] = 0

    def anchor(self, t: float, y: np.ndarray) -> None:
        k = self.kernels
        if not (
            self.vec[k.TIMES, 0] == t and np.array_equal(self.vec[k.Q, self.independent], y[: self.size])
        ):
            self.positions(t, y[: self.size])
        k.anchor(self.index, self.vec, self.jacs, self.matrices)

    def _run(self, level: int, t: float, y: np.ndarray, out: np.ndarray) -> None:
        status, _ = self.partitioned(level, t, y, out, *self.arguments)
        if status != self.ok:
            self._retry(status, level, t, y, out)

    def _retry(self, status: int, level: int, t: float, y: np.ndarray, out: np.ndarray) -> None:
        """An unconverged call once more as the plain path makes it, from the tangent predictor with
        C_D factored at every iteration (no chord), and stalled accepted below RETRY_STALLED rather
        than STALLED; raises if that fails too. It was added for slider_crank_spring/undamped at
        rtol 1e-6, where Newton on the compiled rows stalled at 3.9e-12 at t=0.78: a symptom of
        Newton started from rejected trial stages (the rod's angle had wandered to -1.9e5 rad, where
        sin and cos carry 3e-11 of round-off). Since Newton starts from the last accepted step
        (`anchor`), no call of the dynamics suite's scenes at rtol 1e-6, 1e-8 or 1e-10 reaches it
        (counted); it stays as the plain path's own Newton behind the chord."""
        residual = math.nan
        k = self.kernels
        if status == k.NOT_CONVERGED:
            self.index[k.SIZES, k.S_CHORD], self.vec[k.TOL, 1] = 0, RETRY_STALLED
            try:
                status, residual = self.partitioned(level, t, y, out, *self.arguments)
            finally:
                self.index[k.SIZES, k.S_CHORD], self.vec[k.TOL, 1] = 1, STALLED
        if status != self.ok:
            self._fail(status, t, residual)

    def _fail(self, status: int, t: float, residual: float) -> None:
        if status == self.kernels.NOT_CONVERGED:
            raise ConvergenceError(
                f"{self.system.scenario.name}: the dependent coordinates did not converge at t={t:.6g} "
                f"(constraint residual {residual:.2g})",
                time=t,
                q=self.vec[self.kernels.QT, : self.n].copy(),
            )
        raise np.linalg.LinAlgError("the reduced mass matrix has an exactly zero pivot")

    def conditioning(self, jac: np.ndarray) -> float:
        return float(self.kernels.conditioning(np.ascontiguousarray(jac), self.index, self.vec))

    def positions(self, t: float, q_independent: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        self._run(self.kernels.POSITIONS, float(t), np.ascontiguousarray(q_independent), self.nothing)
        return self.vec[self.kernels.Q, : self.n].copy(), self.jacs[0].reshape(self.m, self.n).copy()

    def state(self, t: float, y: np.ndarray) -> State:
        k, n, m = self.kernels, self.n, self.m
        self._run(k.STATE, float(t), np.ascontiguousarray(y), self.nothing)
        vec = self.vec
        potential, applied, dissipation = (float(v) for v in vec[k.TOTALS, :3])
        loads = LoadState(vec[k.QE, :n].copy(), potential, applied, dissipation)
        return State(
            float(t),
            vec[k.Q, :n].copy(),
            vec[k.QD, :n].copy(),
            vec[k.QDD, :n].copy(),
            vec[k.LAM, :m].copy(),
            self.jacs[0].reshape(m, n).copy(),
            loads,
        )

    def rates(self, t: float, y: np.ndarray) -> np.ndarray:
        """The right-hand side (y a column of a matrix where Radau differentiates it numerically)."""
        self.evaluations += 1
        if not y.flags.c_contiguous:
            y = np.ascontiguousarray(y)  # one compiled version of the kernel: contiguous arrays
        out = np.empty(self.outputs)
        status, _ = self.partitioned(self.level, t, y, out, *self.arguments)
        if status != self.ok:
            self._retry(status, self.level, t, y, out)
        return out


def partitioned_ode(
    system: ConstraintSystem, mass: np.ndarray, loads: Loads, q: np.ndarray, independent: np.ndarray
) -> Partitioned:
    """CompiledPartitioned where the system is compiled and its loads compile, else Partitioned."""
    if isinstance(system, CompiledSystem):
        kernels, _ = rates_kernels()
        if kernels is not None:
            try:
                return CompiledPartitioned(system, mass, loads, q, independent, kernels)
            except NotCompiled:
                pass
    return Partitioned(system, mass, loads, q, independent)
