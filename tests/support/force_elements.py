"""Every force element kind on two bodies, and random states to evaluate them on."""

from __future__ import annotations

import numpy as np

from reference_solver.dynamics.loads import Loads
from reference_solver.layout import Layout
from scenarios import GROUND, Body, Harmonic, Point, Scenario
from scenarios.forces import AppliedForce, AppliedTorque, Force, RotationalSpringDamper, SpringDamper

BODIES = (
    Body("a", (0.1, 0.2, 0.3), mass=2.0, inertia=0.1),
    Body("b", (-0.2, 0.4, 1.1), mass=0.5, inertia=0.02),
)
CASES: dict[str, tuple[Force, ...]] = {
    "spring": (SpringDamper("s", Point("a", (0.3, -0.1)), Point("b", (-0.2, 0.15)), 120.0, 0.0, 0.25),),
    "spring_to_ground": (
        SpringDamper("s", Point(GROUND, (1.0, -0.5)), Point("b", (0.1, 0.2)), 80.0, 0.0, 0.4),
    ),
    "damper": (SpringDamper("s", Point("a", (0.3, -0.1)), Point("b", (-0.2, 0.15)), 0.0, 3.0, 0.25),),
    "torsion": (RotationalSpringDamper("r", "a", "b", 7.0, 0.0, 0.3),),
    "torsion_damper": (RotationalSpringDamper("r", GROUND, "b", 0.0, 1.5, 0.0),),
    "torsion_damper_pair": (RotationalSpringDamper("r", "a", "b", 0.0, 2.0, 0.0),),
    "force": (AppliedForce("f", Point("a", (0.2, -0.3)), Harmonic(3.0, 1.0, 2.5), Harmonic(0.5, 2.0, 4.0)),),
    "torque": (AppliedTorque("t", "a", Harmonic(1.0, 0.5, 3.0), reaction="b"),),
}
RNG = np.random.default_rng(14)
STATES = [(RNG.uniform(-1, 1, 6), RNG.uniform(-2, 2, 6), float(RNG.uniform(0, 2))) for _ in range(40)]


def loads(forces: tuple[Force, ...], gravity: tuple[float, float] = (0.0, 0.0)) -> Loads:
    scenario = Scenario("t", "default", BODIES, (), (), 1.0, 1, 1.0, gravity=gravity, forces=forces)
    layout = Layout.of(scenario)
    return Loads(scenario, layout, np.array([2.0, 2.0, 0.1, 0.5, 0.5, 0.02]))
