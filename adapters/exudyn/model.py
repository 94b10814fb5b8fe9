"""Build an Exudyn multibody system from an engine-neutral scenario, walking its bodies, joints,
gears, cams and drivers.

Every body is a `NodeRigidBody2D` with reference coordinates zero, so its coordinates are the
textbook's absolute (x, y, theta), and an `ObjectRigidBody2D` (centre of mass at the frame origin).
Exudyn's own elements carry what they can: revolute and prismatic 2D joints, distance connectors
(massless links, knife-edge and roller followers on a circular disc cam), coordinate constraints for
drivers and gears (time-dependent offsets as symbolic user functions where the motion is one Exudyn
can record, Python ones otherwise), and a coordinate-vector connector with linear scaling for a gear
on a moving carrier. The rest (general cam profiles, flat faces, rack and pinion, point drivers) is a
coordinate-vector connector with constraint and Jacobian user functions (adapters.exudyn.constraints),
a cam's contact parameter phi being one more ODE2 coordinate on its own node.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from typing import Any

import exudyn as exu
import numpy as np
from exudyn.itemInterface import (
    MarkerBodyPosition,
    MarkerBodyRigid,
    MarkerNodeCoordinate,
    MarkerNodeCoordinates,
    MarkerObjectODE2Coordinates,
    NodeGenericODE2,
    NodePointGround,
    NodeRigidBody2D,
    ObjectConnectorCoordinate,
    ObjectConnectorCoordinateVector,
    ObjectConnectorDistance,
    ObjectGenericODE2,
    ObjectGround,
    ObjectJointPrismatic2D,
    ObjectJointRevolute2D,
    ObjectRigidBody2D,
    SensorNode,
)

from adapters.exudyn.constraints import UserConstraint, user_constraint
from adapters.exudyn.disc import PhiFromPoses, disc_contact, flat_face_disc
from adapters.exudyn.force_sensors import ForceSensor, add_force_sensors
from adapters.exudyn.loads import add_loads
from adapters.exudyn.user_functions import constraint_functions, offset_functions
from scenarios.bodies import GROUND, Point
from scenarios.cam_profiles import EccentricDisc
from scenarios.cams import CamContact, FlatFaceCam, KnifeEdgeCam, RollerCam
from scenarios.drivers import AbsoluteDriver, RelativeRotationDriver
from scenarios.gears import GearPair, RackPinion
from scenarios.geometry import unit
from scenarios.joints import Ground, Prismatic, Revolute, RevoluteRevolute
from scenarios.motions import Motion
from scenarios.scenario import Scenario

COORDINATE = {"x": 0, "y": 1, "theta": 2}
Term = tuple[str, int, float]  # body, coordinate index, coefficient


class ModelError(ValueError):
    """The scenario holds something this builder cannot represent faithfully in Exudyn."""


@dataclass
class ExudynModel:
    """An assembled-later Exudyn system and what reading its results needs."""

    scenario: Scenario
    container: Any
    mbs: Any
    index: dict[str, int] = field(default_factory=dict)  # body -> first ODE2 index
    phi_index: dict[str, int] = field(default_factory=dict)  # '<contact>.phi' -> its ODE2 index
    phi_from_poses: dict[str, tuple[str, str, PhiFromPoses, float]] = field(default_factory=dict)
    guess: np.ndarray = field(default_factory=lambda: np.zeros(0))
    keep: list[Any] = field(default_factory=list)  # symbolic user functions must stay alive
    native_cams: bool = True
    sensors: list[tuple[int, int, tuple[Any, Any, Any]]] = field(default_factory=list)
    """(first ODE2 index, width, sensors of coordinates, velocities, accelerations) per node: Exudyn
    records the grid states itself (adapters.exudyn.simulation reads them)."""
    force_sensors: list[ForceSensor] = field(default_factory=list)
    """Drivers' forces and joints' reactions (adapters.exudyn.force_sensors)."""
    run_in_starts: dict[tuple[float, float, int], Any] = field(default_factory=dict)
    """The assembled states a run-in starts from (or why there is none), per (first output time,
    step, steps of run-in) (adapters.exudyn.run_in.run_in_start)."""


def build_model(scenario: Scenario, mass_scale: float = 1.0, native_cams: bool = True) -> ExudynModel:
    """The Exudyn system of `scenario`; `native_cams` False sends disc cams through user functions too."""
    container = exu.SystemContainer()
    mbs = container.AddSystem()
    model = ExudynModel(scenario, container, mbs, native_cams=native_cams)
    builder = _Builder(model, mass_scale)
    built: dict[str, tuple[object, list[int]]] = {}
    for item in (*scenario.joints, *scenario.drivers):
        first = mbs.systemData.NumberOfObjects()
        builder.add(item)
        built[item.name] = (item, list(range(first, mbs.systemData.NumberOfObjects())))
    add_loads(mbs, scenario, builder.objects, builder.nodes, builder.at, builder.ground_coordinate)
    if mass_scale == 1.0:  # other masses give other forces than the scenario's
        model.force_sensors = add_force_sensors(mbs, built)
    else:
        warnings.warn(
            f"forces not given: masses scaled by {mass_scale:g}, so the forces are not the scenario's",
            stacklevel=2,
        )
    recorded = [(node, 3) for node in builder.nodes.values()] + [(n, 1) for n in builder.phi_nodes.values()]
    sensors = [(node, width, _state_sensors(mbs, node)) for node, width in recorded]
    mbs.Assemble()
    model.sensors = [(mbs.GetNodeODE2Index(node), width, handles) for node, width, handles in sensors]
    model.index = {b: mbs.GetNodeODE2Index(n) for b, n in builder.nodes.items()}
    model.phi_index = {c: mbs.GetNodeODE2Index(n) for c, n in builder.phi_nodes.items()}
    model.guess = np.array(mbs.systemData.GetODE2Coordinates(exu.ConfigurationType.Initial))
    return model


def _state_sensors(mbs: Any, node: Any) -> tuple[Any, Any, Any]:
    """Sensors storing a node's coordinates, velocities and accelerations in memory (no file)."""
    kinds = (
        exu.OutputVariableType.Coordinates,
        exu.OutputVariableType.Coordinates_t,
        exu.OutputVariableType.Coordinates_tt,
    )
    q, v, a = (
        mbs.AddSensor(
            SensorNode(nodeNumber=node, storeInternal=True, writeToFile=False, outputVariableType=k)
        )
        for k in kinds
    )
    return q, v, a


class _Builder:
    def __init__(self, model: ExudynModel, mass_scale: float) -> None:
        self.model, self.mbs = model, model.mbs
        mbs = self.mbs
        self.ground = mbs.AddObject(ObjectGround())
        ground_node = mbs.AddNode(NodePointGround())
        self.ground_coordinate = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=ground_node, coordinate=0))
        self.nodes: dict[str, Any] = {}
        self.objects: dict[str, Any] = {GROUND: self.ground}
        self.phi_nodes: dict[str, Any] = {}
        for body in model.scenario.bodies:
            node = mbs.AddNode(
                NodeRigidBody2D(
                    referenceCoordinates=[0.0] * 3, initialCoordinates=body.guess, initialVelocities=body.rate
                )
            )
            self.nodes[body.name] = node
            self.objects[body.name] = mbs.AddObject(
                ObjectRigidBody2D(
                    nodeNumber=node, mass=mass_scale * body.mass, inertia=mass_scale * body.inertia
                )
            )

    # --- dispatch ---------------------------------------------------------------------------
    def add(self, item: object) -> None:
        if isinstance(item, Revolute):
            self.mbs.AddObject(ObjectJointRevolute2D(markerNumbers=[self.at(item.p_i), self.at(item.p_j)]))
        elif isinstance(item, Prismatic):
            self.prismatic(item)
        elif isinstance(item, RevoluteRevolute):
            self.distance(item.p_i, item.p_j, item.length)
        elif isinstance(item, Ground):
            for k, value in enumerate(item.pose):
                self.linear([(item.body, k, 1.0)], value)
        elif isinstance(item, GearPair):
            self.gear(item)
        elif isinstance(item, AbsoluteDriver):
            self.linear([(item.body, COORDINATE[item.coordinate], 1.0)], 0.0, item.motion)
        elif isinstance(item, RelativeRotationDriver):
            self.linear([(item.body_i, 2, 1.0), (item.body_j, 2, -1.0)], 0.0, item.motion)
        elif isinstance(item, RackPinion) and self.rack_angle(item) is not None:
            self.rack(item)
        elif isinstance(item, KnifeEdgeCam | RollerCam) and self.disc(item) is not None:
            self.disc_contact(item)
        elif isinstance(item, FlatFaceCam) and self.disc(item) is not None:
            self.flat_face(item)
        else:
            constraint = user_constraint(item)
            if constraint is None:
                raise ModelError(
                    f"no Exudyn element for {type(item).__name__} '{getattr(item, 'name', '?')}'"
                )
            self.user(constraint)

    # --- Exudyn's own elements -------------------------------------------------------------------
    def at(self, point: Point) -> Any:
        return self.mbs.AddMarker(
            MarkerBodyPosition(bodyNumber=self.objects[point.body], localPosition=[*point.local, 0.0])
        )

    def rigid(self, point: Point) -> Any:
        return self.mbs.AddMarker(
            MarkerBodyRigid(bodyNumber=self.objects[point.body], localPosition=[*point.local, 0.0])
        )

    def prismatic(self, joint: Prismatic) -> None:
        # Exudyn keeps the marker-1 normal across the axis; in body j's frame the axis is turned by
        # the constant relative angle theta_i - theta_j.
        ax, ay = unit(joint.axis)
        c, s = math.cos(joint.angle), math.sin(joint.angle)
        axis_j = (c * ax - s * ay, s * ax + c * ay)
        self.mbs.AddObject(
            ObjectJointPrismatic2D(
                markerNumbers=[self.rigid(joint.p_i), self.rigid(joint.p_j)],
                axisMarker0=[ax, ay, 0.0],
                normalMarker1=[-axis_j[1], axis_j[0], 0.0],
                constrainRotation=True,
            )
        )

    def distance(self, p_i: Point, p_j: Point, length: float) -> None:
        if not length > 0.0:
            raise ModelError(f"Exudyn's distance connector needs a positive distance, got {length}")
        self.mbs.AddObject(
            ObjectConnectorDistance(markerNumbers=[self.at(p_i), self.at(p_j)], distance=length)
        )

    def gear(self, gear: GearPair) -> None:
        sign = -1.0 if gear.internal else 1.0
        ri, rj = gear.radius_i, sign * gear.radius_j
        terms = [(gear.gear_i, 2, ri), (gear.gear_j, 2, rj), (gear.carrier, 2, -(ri + rj))]
        rhs = ri * gear.theta0_i + rj * gear.theta0_j - (ri + rj) * gear.theta0_carrier
        self.linear(terms, rhs)

    def linear(self, terms: list[Term], constant: float, motion: Motion | None = None) -> None:
        """sum(coefficient * q) = constant + f(t): a coordinate constraint, or a coordinate-vector
        connector with linear scaling for three coordinates or more."""
        merged: dict[tuple[str, int], float] = {}
        for body, k, coefficient in terms:
            if body != GROUND:  # the ground's coordinates are all zero
                merged[(body, k)] = merged.get((body, k), 0.0) + coefficient
        live = [(b, k, c) for (b, k), c in merged.items() if c != 0.0]
        if not live:
            raise ModelError("a linear constraint with no moving coordinate")
        if len(live) > 2:
            if motion is not None:
                raise ModelError("a time-dependent relation of more than two coordinates")
            self.scaled(live, constant)
            return
        # Exudyn's coordinate constraint: factor1 q[m1] - q[m0] - offset = 0.
        (b1, k1, c1), rest = live[-1], live[:-1]
        m1 = self.coordinate(b1, k1)
        if rest:
            (b0, k0, c0) = rest[0]
            m0, factor, scale = self.coordinate(b0, k0), -c1 / c0, -1.0 / c0
        else:
            m0, factor, scale = self.ground_coordinate, 1.0, 1.0 / c1
        self.mbs.AddObject(
            ObjectConnectorCoordinate(
                markerNumbers=[m0, m1],
                factor1=factor,
                offset=scale * constant,
                **self.offset_functions(motion, scale, scale * constant),
            )
        )

    def coordinate(self, body: str, k: int) -> Any:
        return self.mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=self.nodes[body], coordinate=k))

    def offset_functions(self, motion: Motion | None, scale: float, base: float) -> dict[str, Any]:
        """offset(t) = base + scale f(t) and its rate, symbolic when the motion allows."""
        if motion is None:
            return {}
        functions, keep = offset_functions(self.mbs, motion, scale, base)
        self.model.keep.extend(keep)
        return functions

    def scaled(self, terms: list[Term], constant: float) -> None:
        nodes = list(dict.fromkeys(b for b, _, _ in terms))
        markers, columns = self.coordinate_markers(nodes)
        rows = [np.zeros((1, n)) for n in columns]
        where = {
            b: (0 if i < len(nodes) - 1 else 1, 3 * i if i < len(nodes) - 1 else 0)
            for i, b in enumerate(nodes)
        }
        for body, k, coefficient in terms:
            marker, start = where[body]
            rows[marker][0, start + k] = coefficient
        # Exudyn's coordinate-vector connector: S0 q_m0 - S1 q_m1 + offset = 0.
        self.mbs.AddObject(
            ObjectConnectorCoordinateVector(
                markerNumbers=markers, scalingMarker0=rows[0], scalingMarker1=-rows[1], offset=[-constant]
            )
        )

    # --- rack and pinion on a guided rack ------------------------------------------------------------
    def rack_angle(self, item: RackPinion) -> float | None:
        """The rack's constant angle when a prismatic guide on the ground holds it and the pinion's
        centre is its frame origin: then the mesh row is linear in the coordinates (else None)."""
        if item.centre.local != (0.0, 0.0):
            return None
        rack = item.rack.body
        for joint in self.model.scenario.joints:
            if isinstance(joint, Prismatic) and {joint.p_i.body, joint.p_j.body} == {rack, GROUND}:
                return joint.angle if joint.p_i.body == rack else -joint.angle
        return None

    def rack(self, item: RackPinion) -> None:
        """u.(x_rack + R(th_r) p - x_pinion) - radius (th_pinion - th_rack) = offset with th_r fixed:
        one linear coordinate-vector connector, no user function."""
        angle = self.rack_angle(item)
        assert angle is not None
        c, s = math.cos(angle), math.sin(angle)
        ax, ay = unit(item.axis)
        u = (c * ax - s * ay, s * ax + c * ay)
        px, py = item.rack.local
        pitch = u[0] * (c * px - s * py) + u[1] * (s * px + c * py)
        rack, pinion = item.rack.body, item.centre.body
        terms = [(rack, 0, u[0]), (rack, 1, u[1]), (rack, 2, item.radius)]
        terms += [(pinion, 0, -u[0]), (pinion, 1, -u[1]), (pinion, 2, -item.radius)]
        self.linear(terms, item.offset - pitch)

    # --- cams on a circular disc -------------------------------------------------------------------
    def disc(self, cam: CamContact) -> EccentricDisc | None:
        native = self.model.native_cams and isinstance(cam.profile, EccentricDisc)
        return cam.profile if native else None  # type: ignore[return-value]

    def disc_contact(self, cam: KnifeEdgeCam | RollerCam) -> None:
        disc = self.disc(cam)
        assert disc is not None
        contact = disc_contact(self.model.scenario, cam, disc)
        self.distance(contact.centre, contact.follower, contact.reach)
        self.model.phi_from_poses[cam.name] = (cam.cam, contact.follower.body, contact.phi, cam.phi_guess)

    def flat_face(self, cam: FlatFaceCam) -> None:
        """Exudyn's 2D prismatic joint without its rotation row: (p1 - p0).A1 n1 = 0 with p0 the
        disc's centre and p1 on the follower, R from the face towards the disc."""
        disc = self.disc(cam)
        assert disc is not None
        contact = flat_face_disc(self.model.scenario, cam, disc)
        self.mbs.AddObject(
            ObjectJointPrismatic2D(
                markerNumbers=[self.rigid(contact.centre), self.rigid(contact.slider)],
                axisMarker0=[1.0, 0.0, 0.0],
                normalMarker1=[*contact.normal, 0.0],
                constrainRotation=False,
            )
        )
        self.model.phi_from_poses[cam.name] = (cam.cam, contact.slider.body, contact.phi, cam.phi_guess)

    # --- user-function connectors -------------------------------------------------------------------
    def coordinate_markers(self, nodes: list[Any]) -> tuple[list[Any], list[int]]:
        """Two coordinate markers covering `nodes` (bodies or phi keys): all but the last node on
        the first (through a massless generic object when there are several), the last on the
        second; one node alone is covered by the same marker twice."""
        handles = [self.nodes[n] if n in self.nodes else self.phi_nodes[n] for n in nodes]
        sizes = [3 if n in self.nodes else 1 for n in nodes]
        last = self.mbs.AddMarker(MarkerNodeCoordinates(nodeNumber=handles[-1]))
        if len(handles) == 1:
            return [last, last], [sizes[0], sizes[0]]
        if len(handles) == 2:
            first = self.mbs.AddMarker(MarkerNodeCoordinates(nodeNumber=handles[0]))
        else:
            size = sum(sizes[:-1])
            group = self.mbs.AddObject(
                ObjectGenericODE2(nodeNumbers=handles[:-1], massMatrix=np.zeros((size, size)))
            )
            first = self.mbs.AddMarker(MarkerObjectODE2Coordinates(objectNumber=group))
        return [first, last], [sum(sizes[:-1]), sizes[-1]]

    def user(self, constraint: UserConstraint) -> None:
        nodes = [b for b in constraint.bodies if b != GROUND]
        if len(set(nodes)) != len(nodes):
            raise ModelError(f"'{constraint.name}' names the same body twice")
        if constraint.extra:
            key = f"{constraint.name}.phi"
            guess = float(getattr(_item(self.model.scenario, constraint.name), "phi_guess", 0.0))
            self.phi_nodes[key] = self.mbs.AddNode(
                NodeGenericODE2(
                    referenceCoordinates=[0.0],
                    initialCoordinates=[guess],
                    initialCoordinates_t=[0.0],
                    numberOfODE2Coordinates=1,
                )
            )
            nodes.append(key)
        markers, columns = self.coordinate_markers(nodes)
        functions = constraint_functions(constraint, sum(columns))
        self.mbs.AddObject(
            ObjectConnectorCoordinateVector(
                markerNumbers=markers,
                scalingMarker0=np.zeros((constraint.size, 1)),
                constraintUserFunction=functions[0],
                jacobianUserFunction=functions[1],
            )
        )


def _item(scenario: Scenario, name: str) -> object:
    for item in (*scenario.joints, *scenario.drivers):
        if getattr(item, "name", None) == name:
            return item
    raise KeyError(name)
