"""Inverse dynamics of a kinematically driven mechanism: q, q', q'' from the kinematic analysis,
then lambda from the first block row, C_q^T lambda = Q_e - M q''. The drivers' rows of -C_q^T lambda
are the forces and torques they must apply; the joints' rows their reactions."""

from __future__ import annotations

import numpy as np
from scipy.linalg import lstsq

from reference_solver.compiled_system import constraint_system
from reference_solver.dynamics.augmented import constraint_outputs
from reference_solver.dynamics.loads import Loads
from reference_solver.dynamics.mass import mass_diagonal
from reference_solver.solution import Analysis
from scenarios.scenario import Scenario


def inverse_dynamics(scenario: Scenario, analysis: Analysis) -> dict[str, np.ndarray]:
    """Driver forces, joint reactions, kinetic and potential energy on the analysis grid. The
    Jacobian is the compiled one where the scenario compiles (equal to the plain rows to 1e-13,
    tests/reference_solver/test_compiled_system.py), about 3 times faster for a truth's forces."""
    system = constraint_system(scenario)
    mass = mass_diagonal(scenario, system.layout, massless_contacts=True)
    loads = Loads(scenario, system.layout, mass)
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
