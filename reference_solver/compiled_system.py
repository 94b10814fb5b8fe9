"""The constraint system through the compiled path's kernels, for forward dynamics.

Every right-hand side of the partitioned integrator evaluates C (Newton on the dependent
coordinates), C_q, C_t and Q_d; in plain Python that costs milliseconds. `constraint_system` gives
the same ConstraintSystem whose `evaluate` and `c_t` run the compiled row instructions
(reference_solver.compiled.program.compile_dense, compiled.dense) instead, when the scenario compiles;
the plain system otherwise, or when asked (`compiled=False`), so that each path checks the other.
"""

from __future__ import annotations

import warnings
from types import ModuleType

import numpy as np

from reference_solver.compiled import dense_kernels
from reference_solver.compiled.constraint_rows import NotCompiled
from reference_solver.compiled.program import compile_dense
from reference_solver.system import ConstraintSystem
from scenarios.scenario import Scenario


class CompiledSystem(ConstraintSystem):
    """A ConstraintSystem whose C, C_q, Q_d and C_t come from compiled kernels (`dense`, the
    compiled.dense module); NotCompiled where its rows have no kernel."""

    def __init__(self, scenario: Scenario, dense: ModuleType) -> None:
        super().__init__(scenario)
        self.kernels = dense.DenseKernels(compile_dense(self))

    def evaluate(
        self, q: np.ndarray, t: float, qd: np.ndarray | None = None
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        q = np.ascontiguousarray(q, dtype=float)
        qd = np.zeros_like(q) if qd is None else np.ascontiguousarray(qd, dtype=float)
        return self.kernels.evaluate(q, qd, t)  # type: ignore[attr-defined, no-any-return]

    def c_t(self, t: float) -> np.ndarray:
        return self.kernels.c_t(t)  # type: ignore[attr-defined, no-any-return]


def constraint_system(scenario: Scenario, compiled: bool = True) -> ConstraintSystem:
    """The compiled system where the scenario compiles and `compiled`, else the plain one."""
    if not compiled or scenario.cams:
        return ConstraintSystem(scenario)
    module, problem = dense_kernels()
    if module is None:
        warnings.warn(f"native dynamics: the plain path runs, {problem}", RuntimeWarning, stacklevel=2)
        return ConstraintSystem(scenario)
    try:
        return CompiledSystem(scenario, module)
    except NotCompiled:
        return ConstraintSystem(scenario)
