"""One start for every engine in free dynamics: the native solver's assembled, consistent state.

A dynamic scenario's guesses need not satisfy its constraints, and every engine assembles them its
own way (the native solver by minimum-norm Newton in absolute coordinates, MuJoCo and Pinocchio in
joint coordinates, Exudyn not at all): a guess 1 mm off gave starts 3e-3 m apart. So the runner hands
every engine the native assembly (reference_solver.dynamics.forward.initial_state: positions on the
constraints nearest the guesses, rates nearest the given ones in the kinetic-energy norm) as the
bodies' guesses and rates. A scenario whose start is already consistent is returned unchanged.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from scenarios import Scenario

MOVED = 1e-12
"""A start that moves less than this (lengths over the characteristic length, angles, rates over
their largest) is already consistent: the scenario is kept as written."""


def consistent_start(scenario: Scenario) -> Scenario:
    """The scenario with the native assembled start as its bodies' guesses and rates (dynamic only;
    unchanged where the native solver cannot assemble it: every engine then says why itself)."""
    if scenario.analysis != "dynamic":
        return scenario
    from reference_solver.dynamics.forward import initial_state  # on first use: slow to import
    from reference_solver.dynamics.loads import Loads
    from reference_solver.dynamics.mass import mass_diagonal
    from reference_solver.errors import SolverError
    from reference_solver.system import ConstraintSystem

    try:
        system = ConstraintSystem(scenario)
        mass = mass_diagonal(scenario, system.layout)
        start = initial_state(system, mass, Loads(scenario, system.layout, mass), 0.0)
    except SolverError:
        return scenario
    guesses = np.array([b.guess for b in scenario.bodies], dtype=float)
    rates = np.array([b.rate for b in scenario.bodies], dtype=float)
    q, qd = start.q[: guesses.size].reshape(-1, 3), start.qd[: rates.size].reshape(-1, 3)
    scale = np.array([scenario.characteristic_length] * 2 + [1.0])
    rate_scale = max(float(np.max(np.abs(qd), initial=0.0)), 1e-300)
    if np.max(np.abs(q - guesses) / scale) <= MOVED and np.max(np.abs(qd - rates)) <= MOVED * rate_scale:
        return scenario
    bodies = tuple(
        dataclasses.replace(b, guess=_pose(q[k]), rate=_pose(qd[k])) for k, b in enumerate(scenario.bodies)
    )
    return dataclasses.replace(scenario, bodies=bodies)


def _pose(row: np.ndarray) -> tuple[float, float, float]:
    return float(row[0]), float(row[1]), float(row[2])
