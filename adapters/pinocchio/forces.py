"""Driving forces and joint reactions from Pinocchio's inverse dynamics at a run's own states.

At a state (q, v, a) of any mode, the loop-closure and driver rows J carry the forces that make
Pinocchio's tree move so: J^T mu = rnea(q, v, a) - tau_loads (square in a kinematic solve; in free
dynamics the motion makes the system consistent and least squares gives the multipliers the
dynamics applied, `data.lambda_c` of constraintDynamics). A revolute loop row's mu is the force on
p_i's body at p_i (its opposite on p_j's body); a driver's is the force or torque along its
coordinate. Passed to `pin.rnea` as external forces (`fext`, one spatial force per joint in its
own frame) with the applied loads, they leave the tree joints unloaded, and `data.f[i]` is then the
force the parent applies through tree joint i: its reaction (a prismatic's force along its axis
taken out). Columns follow the canonical convention (reports.scoring.forces): `<joint>.fx/.fy` the
force on the joint's first moving body, world axes; `<driver>.force` along the driver's coordinate.
"""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin

from adapters.pinocchio.constraint_rows import ConstraintRows, Snapshot, force_labels
from adapters.pinocchio.loads import Loads
from adapters.pinocchio.model import PinModel
from scenarios.bodies import GROUND, Point
from scenarios.drivers import (
    AbsoluteDriver,
    PointPathDriver,
    RelativeDisplacementDriver,
    RelativeRotationDriver,
)
from scenarios.forces import AppliedForce, AppliedTorque, RotationalSpringDamper, SpringDamper
from scenarios.gears import GearPair
from scenarios.joints import Prismatic, Revolute
from scenarios.scenario import Scenario

Wrench = tuple[Point, np.ndarray, float]
"""A planar force (world axes) at a body point and a couple about z, on that point's body."""


def unsupported(scenario: Scenario, pm: PinModel, constraint_rows: ConstraintRows) -> str | None:
    """Why the forces cannot be read from this model, or None."""
    if pm.tree.mimics:
        return "forces not given: a gear as a mimic joint transmits no force Pinocchio reports"
    for item in constraint_rows.closures:
        if not isinstance(item, Revolute | GearPair):
            return (
                f"forces not given: the {type(item).__name__} '{getattr(item, 'name', '')}' closes a "
                "loop as a row whose force has no body-force form here (revolute and gear rows only)"
            )
    if scenario.cams:
        return "forces not given: a cam contact's force has no body-force form here"
    return None


class ForceReader:
    """The canonical force columns at states of one Pinocchio model."""

    def __init__(self, scenario: Scenario, pm: PinModel, constraint_rows: ConstraintRows) -> None:
        self.scenario, self.pm, self.constraint_rows = scenario, pm, constraint_rows
        self.data = pm.model.createData()
        self.loads = Loads(pm, scenario.forces) if scenario.forces else None
        self.empty = np.zeros(0)
        self.tree_joints = {e.name: e for e in pm.tree.edges if e.kind != "fixed"}
        self.reactions = [
            j for j in scenario.joints if isinstance(j, Revolute | Prismatic) and j.name in self.tree_joints
        ]
        self.closures = [j for j in constraint_rows.closures if isinstance(j, Revolute | GearPair)]
        self.loops = [j for j in self.closures if isinstance(j, Revolute)]
        """The closures with a reaction column: the revolute ones."""

    def columns(self) -> list[str]:
        """The columns `read` fills, in its order."""
        names = [label for driver in self.scenario.drivers for label in force_labels(driver)]
        for joint in (*self.reactions, *self.loops):
            names += [f"{joint.name}.fx", f"{joint.name}.fy"]
        return names

    def read(self, t: float, q: np.ndarray, v: np.ndarray, a: np.ndarray) -> np.ndarray:
        """Every column at one state."""
        model, data = self.pm.model, self.data
        mu = self.empty  # a tree with no drivers: no rows, every joint in the tree
        if self.closures or self.scenario.drivers:
            snapshot = Snapshot(self.pm, data, (q, v, self.empty, self.empty), 0)
            rows = self.constraint_rows.evaluate(snapshot)
            tau = pin.rnea(model, data, q, v, a).copy()
            loads = self.loads.generalized(t, q, v) if self.loads is not None else 0.0
            mu = np.linalg.lstsq(rows.jac[:, : model.nv].T, tau - loads, rcond=None)[0]
        closing = sum(2 if isinstance(j, Revolute) else 1 for j in self.closures)
        wrenches = [*self._closure_wrenches(mu[:closing]), *self._driver_wrenches(mu[closing:])]
        wrenches += self._load_wrenches(t, q, v)
        pin.forwardKinematics(model, data, q, v, a)
        pin.rnea(model, data, q, v, a, self._fext(wrenches))
        out = list(mu[closing:])
        for joint in self.reactions:
            out += list(self._reaction(joint))
        for closure, force in zip(self.closures, self._split(mu[:closing]), strict=True):
            if isinstance(closure, Revolute):
                out += list((1.0 if closure.p_i.body != GROUND else -1.0) * force)
        return np.array(out)

    def _split(self, mu: np.ndarray) -> list[np.ndarray]:
        """The closures' multipliers, one array each (two for a revolute, one for a gear row)."""
        ends = np.cumsum([2 if isinstance(j, Revolute) else 1 for j in self.closures])
        return np.split(mu, ends[:-1]) if self.closures else []

    def _reaction(self, joint: Revolute | Prismatic) -> np.ndarray:
        """The force tree joint `joint` applies to its first moving body, world axes."""
        edge = self.tree_joints[joint.name]
        jid = self.pm.joint_id[joint.name]
        rotation = self.data.oMi[jid].rotation
        force = rotation @ self.data.f[jid].linear
        if isinstance(joint, Prismatic):
            axis = rotation @ np.array([edge.axis[0], edge.axis[1], 0.0])
            force = force - (force @ axis) * axis
        first = joint.p_i.body if joint.p_i.body != GROUND else joint.p_j.body
        return (1.0 if edge.child == first else -1.0) * force[:2]

    def _closure_wrenches(self, mu: np.ndarray) -> list[Wrench]:
        """A revolute row's mu is the force on p_i (its opposite on p_j); a gear row's acts on the
        angles as its law: r_i mu on gear i, r_j mu on gear j (-r_j in a ring), their sum's opposite
        on the carrier."""
        out: list[Wrench] = []
        zero = np.zeros(2)
        for joint, force in zip(self.closures, self._split(mu), strict=True):
            if isinstance(joint, Revolute):
                out += [(joint.p_i, force, 0.0), (joint.p_j, -force, 0.0)]
                continue
            ri, rj = joint.radius_i, -joint.radius_j if joint.internal else joint.radius_j
            m = float(force[0])
            out += [
                (Point(joint.gear_i), zero, ri * m),
                (Point(joint.gear_j), zero, rj * m),
                (Point(joint.carrier), zero, -(ri + rj) * m),
            ]
        return out

    def _driver_wrenches(self, mu: np.ndarray) -> list[Wrench]:
        out: list[Wrench] = []
        zero, k = np.zeros(2), 0
        for driver in self.scenario.drivers:
            if isinstance(driver, AbsoluteDriver) and driver.coordinate == "theta":
                out.append((Point(driver.body), zero, float(mu[k])))
            elif isinstance(driver, AbsoluteDriver):
                axis = np.array([1.0, 0.0] if driver.coordinate == "x" else [0.0, 1.0])
                out.append((Point(driver.body), float(mu[k]) * axis, 0.0))
            elif isinstance(driver, RelativeRotationDriver):
                out += [
                    (Point(driver.body_i), zero, float(mu[k])),
                    (Point(driver.body_j), zero, -float(mu[k])),
                ]
            elif isinstance(driver, PointPathDriver):
                out.append((driver.point, mu[k : k + 2], 0.0))
            elif isinstance(driver, RelativeDisplacementDriver):
                out += [(driver.p_i, mu[k : k + 2], 0.0), (driver.p_j, -mu[k : k + 2], 0.0)]
            k += len(force_labels(driver))
        return out

    def _load_wrenches(self, t: float, q: np.ndarray, v: np.ndarray) -> list[Wrench]:
        """The applied loads as forces on the bodies (gravity is the model's own)."""
        out: list[Wrench] = []
        zero = np.zeros(2)
        for force in self.scenario.forces:
            if isinstance(force, AppliedTorque):
                torque = force.torque.f(t)
                out += [(Point(force.body), zero, torque), (Point(force.reaction), zero, -torque)]
            elif isinstance(force, AppliedForce):
                out.append((force.point, np.array([force.fx.f(t), force.fy.f(t)]), 0.0))
            elif isinstance(force, SpringDamper):
                pull = self._tension(force, q, v)
                out += [(force.p_i, pull, 0.0), (force.p_j, -pull, 0.0)]
            elif isinstance(force, RotationalSpringDamper):
                turn = self.pm.angle(force.body_j, q) - self.pm.angle(force.body_i, q) - force.free_angle
                rate = float((self._row(force.body_j) - self._row(force.body_i)) @ v)
                torque = force.stiffness * turn + force.damping * rate
                out += [(Point(force.body_i), zero, torque), (Point(force.body_j), zero, -torque)]
        return out

    def _row(self, body: str) -> np.ndarray:
        return self.pm.zero_v if body == GROUND else self.pm.angle_row[body]

    def _tension(self, spring: SpringDamper, q: np.ndarray, v: np.ndarray) -> np.ndarray:
        """The spring-damper's pull on p_i (towards p_j), from the point frames at q, v."""
        snapshot = Snapshot(self.pm, self.data, (q, v, self.empty, self.empty), 0)
        gap = snapshot.point(spring.p_j) - snapshot.point(spring.p_i)
        length = math.hypot(*gap.val)
        unit = gap.val / length
        tension = spring.stiffness * (length - spring.free_length) + spring.damping * float(unit @ gap.rate)
        return tension * unit

    def _fext(self, wrenches: list[Wrench]) -> pin.StdVec_Force:
        """The wrenches as Pinocchio's external forces, each in its carrying joint's frame."""
        model, data = self.pm.model, self.data
        pin.updateFramePlacements(model, data)
        fext = pin.StdVec_Force()
        for _ in range(model.njoints):
            fext.append(pin.Force.Zero())
        for point, force, torque in wrenches:
            if point.body == GROUND:
                continue
            frame = model.frames[self.pm.frame_id[point]]  # every used point has a frame
            jid = frame.parentJoint
            linear = data.oMi[jid].rotation.T @ np.array([force[0], force[1], 0.0])
            local = frame.placement.translation
            fext[jid] += pin.Force(linear, np.cross(local, linear) + np.array([0.0, 0.0, torque]))
        return fext
