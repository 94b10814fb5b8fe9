"""The mass matrix in absolute coordinates: diag(m, m, J) per body, J about the centre of mass,
which is the body frame's origin; stored as its diagonal."""

from __future__ import annotations

import numpy as np

from reference_solver.errors import SolverError
from reference_solver.layout import Layout
from scenarios.scenario import Scenario


def mass_diagonal(scenario: Scenario, layout: Layout, massless_contacts: bool = False) -> np.ndarray:
    """The diagonal of M, in the layout's column order. A cam's contact parameter has no inertia:
    forward dynamics refuses it (M would be singular), inverse dynamics takes it as massless
    (`massless_contacts`), its row of C_q^T lambda = Q_e - M q'' then says the contact force is
    normal to the profile."""
    if layout.contacts and not massless_contacts:
        raise SolverError(f"{scenario.name}: dynamics with cam contacts is not supported")
    diagonal = np.zeros(layout.size)
    for k, body in enumerate(scenario.bodies):
        if not (body.mass > 0 and body.inertia > 0):
            raise SolverError(f"{scenario.name}: body {body.name} needs a positive mass and inertia")
        diagonal[3 * k : 3 * k + 3] = (body.mass, body.mass, body.inertia)
    return diagonal
