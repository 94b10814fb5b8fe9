"""The dynamic tier's loads as MuJoCo elements, planned from a scenario and its tree (no MuJoCo here).

As a MuJoCo user models them: gravity is the model's option; an applied torque is a motor actuator
with a site transmission on the body's frame site and `refsite` on the reaction body, so MuJoCo
applies +T to the body and -T to the reaction; an applied force is one motor per global axis at a
site on its point, with `refsite` on the world so the gear is in global axes; a spring-damper
between two points is a spatial tendon between two sites with stiffness, damping and springlength
(MuJoCo's tendon length is the straight distance between the sites, so the spring is exact); a
rotational spring-damper is the stiffness, damping and springref of the hinge joining its pair,
which it can be only where that pair is a tree hinge (a pair closed by a `connect` has no joint).
Kinematic scenes carry no loads: their clocks would absorb them.
"""

from __future__ import annotations

from dataclasses import dataclass

from adapters.mujoco.tree import Tree, TreeError
from scenarios.bodies import GROUND, Point
from scenarios.forces import AppliedForce, AppliedTorque, RotationalSpringDamper, SpringDamper
from scenarios.motions import Constant, Motion
from scenarios.scenario import Scenario

WORLD_SITE = "world_origin"
"""A site at the world origin: the reference of global axes and of the ground's reactions."""


@dataclass(frozen=True)
class Motor:
    """A motor actuator: `gear` (6 numbers, force then torque) on `site`, reacted on `refsite`;
    its control is `law(t)`."""

    name: str
    site: Point
    refsite: str
    gear: tuple[float, float, float, float, float, float]
    law: Motion


@dataclass(frozen=True)
class HingeSpring:
    """Stiffness, damping and rest position (in the hinge's qpos) of a tree hinge."""

    stiffness: float
    damping: float
    springref: float


@dataclass(frozen=True)
class Loads:
    """Gravity (m/s^2, global x and y), motors, tendons and hinge springs by joint name."""

    gravity: tuple[float, float] = (0.0, 0.0)
    motors: tuple[Motor, ...] = ()
    tendons: tuple[SpringDamper, ...] = ()
    """Each spring-damper becomes a spatial tendon between two sites."""
    hinge_springs: tuple[tuple[str, HingeSpring], ...] = ()

    @property
    def constant(self) -> bool:
        """Whether every motor's control is constant in time (set once rather than each stage)."""
        return all(isinstance(motor.law, Constant) for motor in self.motors)


def site_name(p: Point) -> str:
    """The body's frame site at its origin, else a site named after the point."""
    if p.local == (0.0, 0.0):
        return WORLD_SITE if p.body == GROUND else p.body
    return f"{p.body}@{p.local[0]!r},{p.local[1]!r}"


def loads_of(scenario: Scenario, tree: Tree) -> Loads:
    """The scenario's loads; TreeError names one MuJoCo cannot represent faithfully."""
    if scenario.analysis != "dynamic":
        return Loads()
    motors: list[Motor] = []
    tendons: list[SpringDamper] = []
    springs: list[tuple[str, HingeSpring]] = []
    for force in scenario.forces:
        if isinstance(force, AppliedTorque):
            origin = Point(force.body, (0.0, 0.0))
            reaction = site_name(Point(force.reaction, (0.0, 0.0)))
            motors.append(Motor(force.name, origin, reaction, (0.0, 0.0, 0.0, 0.0, 0.0, 1.0), force.torque))
        elif isinstance(force, AppliedForce):
            for axis, law in (("x", force.fx), ("y", force.fy)):
                gear = (1.0, 0.0, 0.0, 0.0, 0.0, 0.0) if axis == "x" else (0.0, 1.0, 0.0, 0.0, 0.0, 0.0)
                motors.append(Motor(f"{force.name}.{axis}", force.point, WORLD_SITE, gear, law))
        elif isinstance(force, SpringDamper):
            tendons.append(force)
        elif isinstance(force, RotationalSpringDamper):
            springs.append(_hinge_spring(force, tree))
    return Loads(scenario.gravity, tuple(motors), tuple(tendons), tuple(springs))


def _hinge_spring(force: RotationalSpringDamper, tree: Tree) -> tuple[str, HingeSpring]:
    """The tree hinge between the pair carries the spring: its qpos is the child's angle relative
    to the parent's less their angle at qpos = 0."""
    pair = {force.body_i, force.body_j}
    joint = next((j for j in tree.joints if {j.parent, j.child} == pair and j.kind == "hinge"), None)
    if joint is None:
        raise TreeError(
            f"rotational spring '{force.name}': its pair is not one tree hinge in MuJoCo (a loop "
            "closure has no joint to carry a spring)"
        )
    theta = {GROUND: 0.0, **{name: pose[2] for name, pose in tree.poses.items()}}
    relative = theta[force.body_j] - theta[force.body_i]
    rest = force.free_angle - relative
    springref = rest if joint.child == force.body_j else -rest
    return joint.name, HingeSpring(force.stiffness, force.damping, springref)
