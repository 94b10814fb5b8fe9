"""Inverse dynamics of a kinematically driven mechanism: q, q', q'' from the kinematic analysis,
then lambda from the first block row, C_q^T lambda = Q_e - M q''. The drivers' rows of -C_q^T lambda
are the forces and torques they must apply; the joints' rows their reactions."""

from __future__ import annotations

import numpy as np
from scipy.linalg import lstsq

from reference_solver.compiled import pays
from reference_solver.compiled_system import constraint_system
from reference_solver.dynamics.augmented import constraint_outputs
from reference_solver.dynamics.compiled_inverse import compiled_outputs
from reference_solver.dynamics.loads import Loads
from reference_solver.dynamics.mass import mass_diagonal
from reference_solver.solution import Analysis
from scenarios.scenario import Scenario


def inverse_dynamics(
    scenario: Scenario, analysis: Analysis, compiled: bool | None = True
) -> dict[str, np.ndarray]:
    """Driver forces, joint reactions, kinetic and potential energy on the analysis grid. Where the
    scenario and its loads compile and `compiled`, the grid in compiled chunks
    (dynamics.compiled_inverse, equal to this loop to 1e-12); otherwise this loop, on the compiled
    Jacobian where the rows compile and `compiled` (equal to the plain rows to 1e-13,
    tests/reference_solver/test_compiled_system.py), on the plain rows without `compiled`.
    `compiled` None is True where the compiled call pays (reference_solver.compiled.pays), else False."""
    compiled = pays("inverse_kernel", analysis.q.shape[1], len(analysis.times), compiled)
    system = constraint_system(scenario, compiled=compiled)
    mass = mass_diagonal(scenario, system.layout, massless_contacts=True)
    loads = Loads(scenario, system.layout, mass)
    if compiled:
        found = compiled_outputs(system, mass, loads, analysis)
        if found is not None:
            return found
    rows: list[dict[str, float]] = []
    for t, q, qd, qdd in zip(analysis.times, analysis.q, analysis.qd, analysis.qdd, strict=True):
        jac = system.jacobian(q, float(t))
        load = loads(q, qd, float(t))
        lam = lstsq(jac.T, load.generalized - mass * qdd, check_finite=False)[0]
        row = constraint_outputs(system, jac, lam)
        row["energy.kinetic"] = 0.5 * float(qd @ (mass * qd))
        row["energy.potential"] = load.potential
        rows.append(row)
    return {key: np.array([r[key] for r in rows]) for key in rows[0]}
