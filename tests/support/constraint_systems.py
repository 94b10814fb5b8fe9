"""A constraint system of bodies a, b and c (all starting at the origin) around given constraints, and
its rows at hand-chosen poses: the value tests of the equations build on it."""

from __future__ import annotations

import numpy as np

from reference_solver.system import ConstraintSystem
from scenarios import Body, Scenario
from scenarios.drivers import Driver
from scenarios.scenario import Constraint

BODIES = ("a", "b", "c")
Pose = tuple[float, float, float]


def system_of(*constraints: Constraint, length: float = 1.0) -> ConstraintSystem:
    """The constraints (drivers after the rest, as a scenario stacks them) on bodies a, b and c."""
    drivers = tuple(c for c in constraints if isinstance(c, Driver))
    joints = tuple(c for c in constraints if not isinstance(c, Driver))
    scenario = Scenario(
        family="test",
        variant="default",
        bodies=tuple(Body(name, (0.0, 0.0, 0.0)) for name in BODIES),
        joints=joints,
        drivers=drivers,
        t_end=1.0,
        steps=1,
        characteristic_length=length,
    )
    return ConstraintSystem(scenario)


def coordinates(poses: dict[str, Pose], phis: tuple[float, ...] = ()) -> np.ndarray:
    """The unknowns with each named body at its pose (the others at the origin), then the cam
    contacts' profile parameters."""
    q = np.zeros(3 * len(BODIES))
    for body, pose in poses.items():
        k = 3 * BODIES.index(body)
        q[k : k + 3] = pose
    return np.concatenate([q, phis])


def residual(
    constraint: Constraint, poses: dict[str, Pose], t: float = 0.0, phis: tuple[float, ...] = ()
) -> np.ndarray:
    """C of one constraint with the bodies at `poses` (and a cam's contact at `phis`)."""
    return system_of(constraint).residual(coordinates(poses, phis), t)
