"""Forces of the dynamic tier: applied loads and spring-dampers acting on the bodies.

Gravity is not here: it is a scenario-level vector (`Scenario.gravity`). Every magnitude that may
vary in time is a motion law (`scenarios.motions`; `Constant` for a constant one). Body frames sit
at the centres of mass, so a force at the frame origin makes no moment.
"""

from __future__ import annotations

from dataclasses import dataclass

from scenarios.bodies import Point
from scenarios.motions import Motion


@dataclass(frozen=True)
class AppliedTorque:
    """A torque `torque(t)` on `body` (counter-clockwise positive); `reaction` (another body or
    the ground) receives minus it, as a motor mounted there would."""

    name: str
    body: str
    torque: Motion
    reaction: str = "ground"


@dataclass(frozen=True)
class AppliedForce:
    """A force (fx(t), fy(t)) in global axes at `point`, fixed on its body."""

    name: str
    point: Point
    fx: Motion
    fy: Motion


@dataclass(frozen=True)
class SpringDamper:
    """A translational spring-damper between points p_i and p_j: tension k (l - l0) + c l_dot
    along the line joining them."""

    name: str
    p_i: Point
    p_j: Point
    stiffness: float
    damping: float = 0.0
    free_length: float = 0.0


@dataclass(frozen=True)
class RotationalSpringDamper:
    """A torsion spring-damper on the revolute pair of body_i and body_j (either may be the ground):
    T = k (theta_j - theta_i - theta0) + c (omega_j - omega_i), +T on body i, -T on body j."""

    name: str
    body_i: str
    body_j: str
    stiffness: float
    damping: float = 0.0
    free_angle: float = 0.0


Force = AppliedTorque | AppliedForce | SpringDamper | RotationalSpringDamper
