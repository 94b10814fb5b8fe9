"""Driving forces and joint reactions by Newton-Euler, body by body, on a given motion.

Each moving body's free-body diagram, its frame at the centre of mass:
    m a = m g + sum of the forces on it,   J alpha = sum of the moments about its centre of mass,
with one unknown force (fx, fy) per revolute joint, one force normal to the axis and one couple per
prismatic joint, three per ground joint, one tangential force per gear mesh (acting on the gears'
angles as the gear law does), and one force or torque per driven coordinate; applied
loads and spring-dampers are evaluated from the motion itself. The equations of all bodies at one
time are a square linear system in the unknowns, solved time by time. Nothing here uses a
constraint Jacobian or a solver: the lever arms are the joints' points on their bodies, so that on
a closed-form motion (scenarios.closed_form) this is a force truth independent of the native
inverse dynamics it is checked against (tests/scenarios/test_newton_euler.py).

The result follows the canonical force columns: `<joint>.fx`, `<joint>.fy` the force the joint
applies to its first moving body (p_i's body, else p_j's), global axes; `<driver>.force` the force or
torque the driver applies along its coordinate (on body_i for a relative rotation).
"""

from __future__ import annotations

import numpy as np

from scenarios.bodies import GROUND, Point
from scenarios.drivers import AbsoluteDriver, RelativeRotationDriver
from scenarios.forces import AppliedForce, AppliedTorque, RotationalSpringDamper, SpringDamper
from scenarios.gears import GearPair
from scenarios.joints import Ground, Prismatic, Revolute
from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory

NEWTON_EULER = "Newton-Euler body by body"
"""The name of this force truth (a row's force truth names it with the motion it was computed on)."""


class NoForceTruth(ValueError):
    """The mechanism has an element the free-body diagrams here do not model (a gear, a cam, a
    point-path driver, a massless link); the message names it."""


class _Diagram:
    """The free-body equations at every grid time: `matrix` (N, 3 bodies, unknowns) times the
    unknowns equals `rhs` (N, 3 bodies); rows per body are (fx, fy, moment)."""

    def __init__(self, scenario: Scenario, motion: Trajectory) -> None:
        self.bodies = [b.name for b in scenario.bodies]
        self.pose = motion.position
        self.velocity = motion.velocity
        if self.pose is None or self.velocity is None or motion.acceleration is None:
            raise NoForceTruth("the motion lacks a level: Newton-Euler needs all three")
        self.index = [motion.bodies.index(b) for b in self.bodies]
        self.times = np.asarray(motion.times, dtype=float)
        self.count = len(self.times)
        self.columns: list[np.ndarray] = []
        self.rhs = np.zeros((self.count, 3 * len(self.bodies)))
        acc = motion.acceleration[:, self.index, :]
        g = np.asarray(scenario.gravity, dtype=float)
        for k, body in enumerate(scenario.bodies):
            self.rhs[:, 3 * k : 3 * k + 2] = body.mass * (acc[:, k, :2] - g)
            self.rhs[:, 3 * k + 2] = body.inertia * acc[:, k, 2]

    def angle(self, body: str) -> np.ndarray:
        if body == GROUND:
            return np.zeros(self.count)
        return self.pose[:, self.index[self.bodies.index(body)], 2]  # type: ignore[index]

    def rate(self, body: str) -> np.ndarray:
        if body == GROUND:
            return np.zeros(self.count)
        return self.velocity[:, self.index[self.bodies.index(body)], 2]  # type: ignore[index]

    def arm(self, point: Point) -> np.ndarray:
        """(N, 2) from the body's centre of mass to the point, world axes (zero on the ground)."""
        if point.body == GROUND:
            return np.zeros((self.count, 2))
        c, s = np.cos(self.angle(point.body)), np.sin(self.angle(point.body))
        x, y = point.local
        return np.stack([c * x - s * y, s * x + c * y], axis=-1)

    def world(self, point: Point) -> np.ndarray:
        """(N, 2) world position of a body point."""
        if point.body == GROUND:
            return np.broadcast_to(np.asarray(point.local, dtype=float), (self.count, 2)).copy()
        origin = self.pose[:, self.index[self.bodies.index(point.body)], :2]  # type: ignore[index]
        return origin + self.arm(point)

    def point_velocity(self, point: Point) -> np.ndarray:
        if point.body == GROUND:
            return np.zeros((self.count, 2))
        v = self.velocity[:, self.index[self.bodies.index(point.body)], :]  # type: ignore[index]
        arm = self.arm(point)
        return v[:, :2] + v[:, 2:3] * np.stack([-arm[:, 1], arm[:, 0]], axis=-1)

    def wrench(self, body: str, force: np.ndarray, arm: np.ndarray, torque: np.ndarray) -> np.ndarray:
        """(N, 3 bodies) of a force (N, 2) applied at `arm` plus a couple, on one body."""
        out = np.zeros((self.count, 3 * len(self.bodies)))
        if body != GROUND:
            k = self.bodies.index(body)
            out[:, 3 * k : 3 * k + 2] = force
            out[:, 3 * k + 2] = arm[:, 0] * force[:, 1] - arm[:, 1] * force[:, 0] + torque
        return out

    def unknown(self, column: np.ndarray) -> None:
        """One unknown: its unit value's contribution to every body's equations."""
        self.columns.append(column)

    def load(self, column: np.ndarray) -> None:
        """A known load: moved to the right-hand side."""
        self.rhs -= column

    def pair(self, first: Point, second: Point, force: np.ndarray, torque: np.ndarray) -> np.ndarray:
        """A force and couple on `first`'s body at `first`, their opposite on `second`'s body along the
        same line of action."""
        line = self.world(first)
        on_second = line - self.world(Point(second.body)) if second.body != GROUND else line
        return self.wrench(first.body, force, self.arm(first), torque) + self.wrench(
            second.body, -force, on_second, -torque
        )

    def solve(self) -> np.ndarray:
        """(N, unknowns) meeting every time's equations: exactly where as many unknowns as equations
        (a driven mechanism), by least squares where fewer (free dynamics, whose motion makes the
        equations consistent); NoForceTruth where more (the forces are not determined)."""
        matrix = np.stack(self.columns, axis=-1)
        if matrix.shape[2] > matrix.shape[1]:
            raise NoForceTruth(
                f"{matrix.shape[2]} unknown forces for {matrix.shape[1]} body equations: the forces "
                "are not determined by the motion"
            )
        if matrix.shape[1] == matrix.shape[2]:
            return np.linalg.solve(matrix, self.rhs[..., None])[..., 0]
        return np.array([np.linalg.lstsq(a, b, rcond=None)[0] for a, b in zip(matrix, self.rhs, strict=True)])


def body_forces(scenario: Scenario, motion: Trajectory) -> dict[str, np.ndarray]:
    """Every revolute's and prismatic's reaction and every driver's force on `motion`'s grid;
    NoForceTruth for a mechanism with an element not modelled here."""
    d = _Diagram(scenario, motion)
    zero, ones, nowhere = np.zeros(d.count), np.ones(d.count), np.zeros((d.count, 2))
    for joint in scenario.joints:
        if isinstance(joint, Revolute | Prismatic):
            first, second = (joint.p_i, joint.p_j) if joint.p_i.body != GROUND else (joint.p_j, joint.p_i)
            for unit in _directions(d, joint):
                d.unknown(d.pair(first, second, unit, zero))
            if isinstance(joint, Prismatic):
                d.unknown(d.pair(first, second, nowhere, ones))  # the couple it transmits
        elif isinstance(joint, GearPair):
            d.unknown(_mesh_column(d, joint))
        elif isinstance(joint, Ground):
            for k in range(3):
                unit = np.zeros((d.count, 3))
                unit[:, k] = 1.0
                d.unknown(d.wrench(joint.body, unit[:, :2], nowhere, unit[:, 2]))
        else:
            raise NoForceTruth(f"no free-body model of the {type(joint).__name__} '{joint.name}'")
    for driver in scenario.drivers:
        d.unknown(_driver_column(d, driver))
    for force in scenario.forces:
        d.load(_load_column(d, force))
    solved = iter(d.solve().T)
    out: dict[str, np.ndarray] = {}
    for joint in scenario.joints:
        if isinstance(joint, Revolute):
            out[f"{joint.name}.fx"], out[f"{joint.name}.fy"] = next(solved), next(solved)
        elif isinstance(joint, Prismatic):
            (normal,) = _directions(d, joint)
            magnitude = next(solved)
            out[f"{joint.name}.fx"], out[f"{joint.name}.fy"] = (magnitude[:, None] * normal).T
            next(solved)  # the couple: no canonical column
        elif isinstance(joint, GearPair):
            next(solved)  # the mesh's tangential force: no canonical column
        else:
            for _ in range(3):
                next(solved)
    for driver in scenario.drivers:
        out[f"{driver.name}.force"] = next(solved)
    return out


def _directions(d: _Diagram, joint: Revolute | Prismatic) -> list[np.ndarray]:
    """The directions of a joint's reaction force: x and y for a revolute, the normal to the sliding
    axis (which turns with body i) for a prismatic."""
    if isinstance(joint, Revolute):
        return [np.tile([1.0, 0.0], (d.count, 1)), np.tile([0.0, 1.0], (d.count, 1))]
    ax, ay = np.asarray(joint.axis, dtype=float) / np.hypot(*joint.axis)
    turn = d.angle(joint.p_i.body)
    c, s = np.cos(turn), np.sin(turn)
    return [np.stack([-(s * ax + c * ay), c * ax - s * ay], axis=-1)]


def _mesh_column(d: _Diagram, gear: GearPair) -> np.ndarray:
    """A unit tangential mesh force as the gear law declares it, a pair of torques on the angles
    alone: r_i on gear i, r_j on gear j (-r_j inside a ring), their sum's opposite on the carrier;
    the mesh does not push the centres, as no engine's gear coupling does."""
    zero, ones = np.zeros((d.count, 2)), np.ones(d.count)
    rj = -gear.radius_j if gear.internal else gear.radius_j
    return (
        d.wrench(gear.gear_i, zero, zero, gear.radius_i * ones)
        + d.wrench(gear.gear_j, zero, zero, rj * ones)
        + d.wrench(gear.carrier, zero, zero, -(gear.radius_i + rj) * ones)
    )


def _driver_column(d: _Diagram, driver: object) -> np.ndarray:
    """The unit driving force's wrenches: a torque on the body (its opposite on body_j for a relative
    rotation), or a force along x or y at the body's frame origin."""
    origin, zero, ones = np.zeros((d.count, 2)), np.zeros(d.count), np.ones(d.count)
    if isinstance(driver, AbsoluteDriver):
        if driver.coordinate == "theta":
            return d.wrench(driver.body, origin, origin, ones)
        unit = np.zeros((d.count, 2))
        unit[:, 0 if driver.coordinate == "x" else 1] = 1.0
        return d.wrench(driver.body, unit, origin, zero)
    if isinstance(driver, RelativeRotationDriver):
        return d.wrench(driver.body_i, origin, origin, ones) + d.wrench(driver.body_j, origin, origin, -ones)
    raise NoForceTruth(f"no free-body model of the {type(driver).__name__} '{getattr(driver, 'name', '')}'")


def _load_column(d: _Diagram, force: object) -> np.ndarray:
    """An applied load's or spring-damper's wrenches at every time, from the motion."""
    origin, zero = np.zeros((d.count, 2)), np.zeros(d.count)
    if isinstance(force, AppliedTorque):
        torque = np.array([force.torque.f(float(t)) for t in d.times])
        return d.wrench(force.body, origin, origin, torque) + d.wrench(
            force.reaction, origin, origin, -torque
        )
    if isinstance(force, AppliedForce):
        pull = np.array([[force.fx.f(float(t)), force.fy.f(float(t))] for t in d.times])
        return d.wrench(force.point.body, pull, d.arm(force.point), zero)
    if isinstance(force, SpringDamper):
        gap = d.world(force.p_j) - d.world(force.p_i)
        length = np.hypot(gap[:, 0], gap[:, 1])
        direction = gap / length[:, None]
        rate = np.sum((d.point_velocity(force.p_j) - d.point_velocity(force.p_i)) * direction, axis=1)
        pull = (force.stiffness * (length - force.free_length) + force.damping * rate)[:, None] * direction
        return d.wrench(force.p_i.body, pull, d.arm(force.p_i), zero) + d.wrench(
            force.p_j.body, -pull, d.arm(force.p_j), zero
        )
    if isinstance(force, RotationalSpringDamper):
        turn = d.angle(force.body_j) - d.angle(force.body_i) - force.free_angle
        rate = d.rate(force.body_j) - d.rate(force.body_i)
        torque = force.stiffness * turn + force.damping * rate
        return d.wrench(force.body_i, origin, origin, torque) + d.wrench(
            force.body_j, origin, origin, -torque
        )
    raise NoForceTruth(f"no model of the load {type(force).__name__}")
