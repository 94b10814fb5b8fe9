"""Scenes for the partitioned method's tests: chains driven or rocked, the released four-bar moved
far from the origin, and counters of what an integration asked for."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable

import numpy as np

import scenarios
from reference_solver.dynamics.forward import initial_state
from reference_solver.dynamics.loads import Loads
from reference_solver.dynamics.mass import mass_diagonal
from reference_solver.dynamics.partition import Partitioned, choose_independent
from reference_solver.system import ConstraintSystem
from scenarios import GROUND, AbsoluteDriver, ConstantSpeed, Harmonic, Point, Revolute, Scenario
from scenarios.forces import AppliedTorque


def driven_chain() -> Scenario:
    """Two links, the first turned at 2 rad/s from its start angle by a driver."""
    chain = scenarios.build("compound_pendulum", overrides={"links": 2, "theta0": 0.3})
    spin = AbsoluteDriver("spin", "link_1", "theta", ConstantSpeed(0.3 - math.pi / 2, 2.0))
    return dataclasses.replace(chain, drivers=(spin,))


def rocked_chain() -> Scenario:
    """Two links, the first rocked harmonically by a driver, the second under a harmonic torque
    (so that C_t and Q_e change with time)."""
    chain = scenarios.build("compound_pendulum", overrides={"links": 2, "theta0": 0.3})
    rock = AbsoluteDriver("rock", "link_1", "theta", Harmonic(0.3 - math.pi / 2, 0.2, 5.0, 0.4))
    motor = AppliedTorque("motor", "link_2", Harmonic(0.0, 1.5, 7.0, 0.1), reaction="link_1")
    return dataclasses.replace(chain, drivers=(rock,), forces=(motor,))


def ode_of(scenario: Scenario, independent: list[int] | None = None) -> tuple[Partitioned, ConstraintSystem]:
    system = ConstraintSystem(scenario)
    mass = mass_diagonal(scenario, system.layout)
    loads = Loads(scenario, system.layout, mass)
    start = initial_state(system, mass, loads, 0.0)
    columns = choose_independent(system, start.jac) if independent is None else np.array(independent)
    return Partitioned(system, mass, loads, start.q, columns), system


def counted(system: ConstraintSystem) -> list[float]:
    """The times at which `system` is evaluated from now on (each one Newton iteration)."""
    calls: list[float] = []
    evaluate: Callable = system.evaluate  # type: ignore[type-arg]

    def counting(q: np.ndarray, t: float):  # type: ignore[no-untyped-def]
        calls.append(t)
        return evaluate(q, t)

    system.evaluate = counting  # type: ignore[method-assign, assignment]
    return calls


SHIFT = 10.0


def four_bar(shift: float) -> Scenario:
    """four_bar_gravity with every ground point and body moved by `shift` along x."""
    scenario = scenarios.build("four_bar_gravity")

    def moved(p: Point) -> Point:
        return Point(p.body, (p.local[0] + shift, p.local[1])) if p.body == GROUND else p

    joints = [j for j in scenario.joints if isinstance(j, Revolute)]
    assert len(joints) == len(scenario.joints)  # four pins
    pins = tuple(dataclasses.replace(j, p_i=moved(j.p_i), p_j=moved(j.p_j)) for j in joints)
    bodies = tuple(dataclasses.replace(b, guess=(b.guess[0] + shift, *b.guess[1:])) for b in scenario.bodies)
    return dataclasses.replace(scenario, joints=pins, bodies=bodies)
