"""Scenes for forward dynamics' tests: a rod and the swinging four-bar, with the tolerance and the
repartition fraction they are run at."""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np

import scenarios
from reference_solver.dynamics.forward import initial_state
from reference_solver.dynamics.loads import Loads
from reference_solver.dynamics.mass import mass_diagonal
from reference_solver.dynamics.partition import State
from reference_solver.system import ConstraintSystem
from scenarios import Body, Harmonic, Scenario
from scenarios.forces import AppliedTorque

RTOL = 1e-9
FRACTION = 0.95


def swinging_four_bar(driven: bool = False) -> Scenario:
    """The released four-bar; `driven`: a harmonic torque on its crank too (a load that depends on
    time, so that the state at a repartition must be taken at the event's time)."""
    scenario = scenarios.build("four_bar_gravity", overrides={"t_end": 0.25, "steps": 5})
    if not driven:
        return scenario
    return dataclasses.replace(
        scenario, forces=(AppliedTorque("motor", "crank", Harmonic(0.0, 0.05, 20.0, 0.0)),)
    )


def rod(**changes: Any) -> Scenario:
    """compound_pendulum's one link (l = 0.5, m = 1, J = m l^2 / 12) pinned at its end, from 0.3 rad."""
    return dataclasses.replace(
        scenarios.build("compound_pendulum", overrides={"links": 1, "theta0": 0.3}), **changes
    )


THROWN = (0.7, -0.4, 3.0)
"""Rates (x', y', theta') given to the rod's body, not consistent with its pin."""


def thrown_rod() -> tuple[Body, State, float]:
    """The rod given the rates THROWN: its body, forward dynamics' consistent start and its angle."""
    base = rod()
    (body,) = base.bodies
    scenario = dataclasses.replace(base, bodies=(dataclasses.replace(body, rate=THROWN),))
    system = ConstraintSystem(scenario)
    mass = mass_diagonal(scenario, system.layout)
    return body, initial_state(system, mass, Loads(scenario, system.layout, mass), 0.0), 0.3 - math.pi / 2


def nearest_turn(body: Body, theta: float) -> tuple[np.ndarray, float]:
    """(a, omega): the rod's centre moves at omega a with a = (l / 2)(-sin, cos) of theta; the rates
    nearest to THROWN in the metric diag(m, m, J) have omega = (m a . v + J w) / (m |a|^2 + J)."""
    a = 0.25 * np.array([-math.sin(theta), math.cos(theta)])
    m, inertia = body.mass, body.inertia
    return a, (m * a @ THROWN[:2] + inertia * THROWN[2]) / (m * a @ a + inertia)
