"""A rod swinging under gravity, and ALI3-P's start on it, for the tests of ALI3-P's compiled step."""

from __future__ import annotations

import numpy as np

import scenarios
from reference_solver.compiled_system import constraint_system
from reference_solver.dynamics.ali3p import Ali3p, StepState
from reference_solver.dynamics.compiled_ali3p import CompiledAli3p, ali3p_stepper
from reference_solver.dynamics.forward import initial_state
from reference_solver.dynamics.loads import Loads
from reference_solver.dynamics.mass import mass_diagonal
from scenarios import Point
from scenarios.drivers import AbsoluteDriver
from scenarios.joints import Revolute
from scenarios.motions import ConstantSpeed

MASS, INERTIA, G, SPEED = 2.0, 0.2, 9.81, 2.0
THETA0 = -np.pi / 2 + 0.3


def swinging_rod() -> scenarios.Scenario:
    """A rod of 1 m pinned at its end, turned at theta = THETA0 + SPEED t under gravity."""
    rod = scenarios.Body(
        "rod", (0.5 * np.cos(THETA0), 0.5 * np.sin(THETA0), THETA0), mass=MASS, inertia=INERTIA, length=1.0
    )
    pin = Revolute("pin", Point("ground", (0.0, 0.0)), Point("rod", (-0.5, 0.0)))
    turn = AbsoluteDriver("turn", "rod", "theta", ConstantSpeed(THETA0, SPEED))
    return scenarios.Scenario(
        "rod", "default", (rod,), (pin,), (turn,), 1.0, 10, 1.0, gravity=(0.0, -G), analysis="dynamic"
    )


def rod_stepper(scenario: scenarios.Scenario, compiled: bool, h: float) -> tuple[Ali3p, Loads, StepState]:
    system = constraint_system(scenario, compiled=compiled)
    mass = mass_diagonal(scenario, system.layout)
    loads = Loads(scenario, system.layout, mass)
    start = initial_state(system, mass, loads, 0.0)
    stepper = ali3p_stepper(system, mass, loads, h)
    return stepper, loads, StepState(start.t, start.q, start.qd, start.qdd, start.lam.copy(), start.jac)


def compiled_stepper_at_rest(scenario: scenarios.Scenario, h: float) -> tuple[CompiledAli3p, StepState]:
    """The compiled ALI3-P stepper on `scenario` (a rod as swinging_rod's, other drivers allowed) and
    the rod at rest at THETA0, its end on the pin, as the step's start (no consistent start solved)."""
    system = constraint_system(scenario)
    mass = mass_diagonal(scenario, system.layout)
    stepper = ali3p_stepper(system, mass, Loads(scenario, system.layout, mass), h)
    assert isinstance(stepper, CompiledAli3p)
    q = np.array([0.5 * np.cos(THETA0), 0.5 * np.sin(THETA0), THETA0])
    return stepper, StepState(
        0.0, q, np.zeros(3), np.zeros(3), np.zeros(system.size), system.jacobian(q, 0.0)
    )
