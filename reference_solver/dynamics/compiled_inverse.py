"""Inverse dynamics of a whole analysis in compiled calls (compiled.inverse_kernel, one chunk of the grid
each: compiled.chunks), where the constraints compile (reference_solver.compiled_system) and every force
element has a kernel (compiled.load_program): the same multipliers, driver forces, reactions and
energies as the plain loop in dynamics.inverse, to 1e-12
(tests/reference_solver/dynamics/test_compiled_inverse.py)."""

from __future__ import annotations

import numpy as np

from reference_solver.compiled import inverse_kernels
from reference_solver.compiled.chunks import chunks, dense_point_seconds
from reference_solver.compiled.constraint_rows import NotCompiled
from reference_solver.compiled.load_program import compile_loads
from reference_solver.compiled_system import CompiledSystem
from reference_solver.dynamics.augmented import output_rows
from reference_solver.dynamics.loads import Loads
from reference_solver.solution import Analysis
from reference_solver.system import ConstraintSystem


def compiled_outputs(
    system: ConstraintSystem, mass: np.ndarray, loads: Loads, analysis: Analysis
) -> dict[str, np.ndarray] | None:
    """Driver forces, joint reactions, kinetic and potential energy on the analysis grid, or None
    where the system or its loads do not compile (the plain loop runs then)."""
    kernels, _ = inverse_kernels()
    if kernels is None or not isinstance(system, CompiledSystem):
        return None
    try:
        forces = compile_loads(loads.forces, system.layout, loads.gravity)
    except NotCompiled:
        return None
    drivers, joints = output_rows(system)
    first = np.full(system.size, -1, np.int64)
    for _, rows, col in joints:
        first[rows] = col
    times = np.ascontiguousarray(analysis.times, dtype=float)
    count, m = times.size, system.size
    lam, pairs, potential = np.empty((count, m)), np.empty((count, m, 2)), np.empty(count)
    dense = system.kernels
    program = dense.program  # type: ignore[attr-defined]
    q, qd, qdd = (np.ascontiguousarray(a, dtype=float) for a in (analysis.q, analysis.qd, analysis.qdd))
    work, scratch = dense.work.copy(), dense.scratch.copy()  # type: ignore[attr-defined]
    for start, stop in chunks(count, dense_point_seconds(m)):  # a signal's handler runs between two
        part = slice(start, stop)
        kernels.multipliers(
            *(program.ints, program.reals, forces.ints, forces.reals, forces.gravity, mass, times[part]),
            *(q[part], qd[part], qdd[part], first, lam[part], pairs[part], potential[part], work, scratch),
        )
    out: dict[str, np.ndarray] = {}
    for name, rows, _ in joints:  # the joints' rows come before the drivers', as constraint_outputs
        force = -pairs[:, rows, :].sum(axis=1)
        out[f"{name}.fx"], out[f"{name}.fy"] = force[:, 0].copy(), force[:, 1].copy()
    out.update({name: -lam[:, row] for name, row in drivers})
    out["energy.kinetic"] = 0.5 * np.einsum("ij,j,ij->i", qd, mass, qd)
    out["energy.potential"] = potential
    return out
