"""A `pinocchio.Model` built from a planned tree: planar joints, bodies with their inertia, and
operational frames at every canonical body frame and every point a constraint or driver uses."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pinocchio as pin

from adapters.pinocchio.tree import Edge, Tree, compose, point_pose
from scenarios.bodies import GROUND, Point, Pose
from scenarios.cams import FlatFaceCam, KnifeEdgeCam, RollerCam
from scenarios.drivers import PointPathDriver, RelativeDisplacementDriver
from scenarios.forces import AppliedForce, SpringDamper
from scenarios.gears import RackPinion
from scenarios.joints import Prismatic, Revolute, RevoluteRevolute
from scenarios.scenario import Scenario


def se3(pose: Pose) -> pin.SE3:
    """A planar pose as a Pinocchio placement (rotation about z)."""
    c, s = math.cos(pose[2]), math.sin(pose[2])
    rotation = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    return pin.SE3(rotation, np.array([pose[0], pose[1], 0.0]))


def frame_jacobian(model: pin.Model, data: pin.Data, frame: int) -> np.ndarray:
    """The (6, nv) LOCAL_WORLD_ALIGNED Jacobian of a frame (a one-column result comes back 1-D)."""
    jac = pin.getFrameJacobian(model, data, frame, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
    return jac if jac.ndim == 2 else jac[:, None]


def _joint_model(edge: Edge) -> pin.JointModel:
    if edge.kind == "revolute":
        return pin.JointModelRZ()
    return pin.JointModelPrismaticUnaligned(np.array([edge.axis[0], edge.axis[1], 0.0]))


def used_points(scenario: Scenario) -> list[Point]:
    """Every point a joint, gear, cam, driver or load refers to, plus each body's frame origin."""
    points = [Point(b) for b in scenario.body_names]
    for item in (*scenario.joints, *scenario.drivers):
        if isinstance(item, Revolute | Prismatic | RevoluteRevolute | RelativeDisplacementDriver):
            points += [item.p_i, item.p_j]
        elif isinstance(item, RackPinion):
            points += [item.centre, item.rack]
        elif isinstance(item, KnifeEdgeCam):
            points.append(item.tip)
        elif isinstance(item, RollerCam):
            points.append(item.centre)
        elif isinstance(item, FlatFaceCam):
            points.append(item.face)
        elif isinstance(item, PointPathDriver):
            points.append(item.point)
    for force in scenario.forces:
        if isinstance(force, SpringDamper):
            points += [force.p_i, force.p_j]
        elif isinstance(force, AppliedForce):
            points.append(force.point)
    return list(dict.fromkeys(points))


@dataclass
class PinModel:
    """The Pinocchio model and what the adapter needs to read it in scenario terms.

    A body's angle is affine in q (every joint turns about z): theta = angle_offset + angle_row @ q.
    """

    model: pin.Model
    tree: Tree
    joint_id: dict[str, int]
    """Pinocchio joint id of each tree edge (by scenario joint name)."""
    frame_id: dict[Point, int]
    """Operational frame of each used point; Point(body) is the body's canonical frame."""
    angle_row: dict[str, np.ndarray] = field(default_factory=dict)
    angle_offset: dict[str, float] = field(default_factory=dict)
    zero_v: np.ndarray = field(init=False)

    def __post_init__(self) -> None:
        self.zero_v = np.zeros(self.model.nv)

    def q_index(self, edge: str) -> int | None:
        """Index of an edge's coordinate in q, or None for a mimic joint (no coordinate of its own)."""
        jid = self.joint_id[edge]
        return int(self.model.idx_qs[jid]) if self.model.nqs[jid] == 1 else None

    def angle(self, body: str, q: np.ndarray) -> float:
        if body == GROUND:
            return 0.0
        return self.angle_offset[body] + float(self.angle_row[body] @ q)

    def q_guess(self) -> np.ndarray:
        q = np.zeros(self.model.nq)
        for edge in self.tree.edges:
            if edge.kind != "fixed" and (k := self.q_index(edge.name)) is not None:
                q[k] = edge.q0
        return q


def depth_first(tree: Tree) -> list[Edge]:
    """The tree's edges in depth-first order: Pinocchio's algorithms on the joint space inertia (crba,
    and through it forwardDynamics and constraintDynamics) take every subtree's joints to be
    contiguous, as its parsers add them; a breadth-first order gives a wrong mass matrix."""
    children: dict[str, list[Edge]] = {}
    for edge in tree.edges:
        children.setdefault(edge.parent, []).append(edge)
    order: list[Edge] = []

    def visit(body: str) -> None:
        for edge in children.get(body, []):
            order.append(edge)
            visit(edge.child)

    visit(GROUND)
    return order


def build_model(scenario: Scenario, tree: Tree) -> PinModel:
    """Joints, inertias and frames from the tree; gear mimics applied last."""
    model = pin.Model()
    # the scenario's gravity in the plane; a kinematically driven scene carries none (Pinocchio's
    # default is -9.81 along z)
    gx, gy = scenario.gravity if scenario.analysis == "dynamic" else (0.0, 0.0)
    model.gravity = pin.Motion(np.array([gx, gy, 0.0]), np.zeros(3))
    model.name = scenario.name
    joint_id: dict[str, int] = {GROUND: 0}
    for edge in depth_first(tree):
        if edge.kind == "fixed":
            continue
        carrier, parent_pose = point_pose(tree, Point(edge.parent))
        placement = se3(compose(parent_pose, edge.parent_frame))
        joint_id[edge.name] = model.addJoint(joint_id[carrier], _joint_model(edge), placement, edge.name)
    for body in scenario.bodies:
        carrier, pose = point_pose(tree, Point(body.name))
        inertia = pin.Inertia(body.mass, np.zeros(3), np.eye(3) * body.inertia)
        model.appendBodyToJoint(joint_id[carrier], inertia, se3(pose))
    frame_id: dict[Point, int] = {}
    for k, point in enumerate(used_points(scenario)):
        carrier, pose = point_pose(tree, point)
        name = point.body if point.local == (0.0, 0.0) else f"{point.body}:p{k}"
        frame = pin.Frame(name, joint_id[carrier], se3(pose), pin.FrameType.OP_FRAME)
        frame_id[point] = model.addFrame(frame)
    for m in tree.mimics:
        model = pin.transformJointIntoMimic(
            model, joint_id[m.primary], joint_id[m.secondary], m.ratio, m.offset
        )
    built = PinModel(model, tree, {k: v for k, v in joint_id.items() if k != GROUND}, frame_id)
    _angles(built, scenario)
    return built


def _angles(built: PinModel, scenario: Scenario) -> None:
    """Each body's angle as an affine function of q, read from Pinocchio at q = 0 and its Jacobian;
    the constant is then shifted by whole turns so that the guess's configuration is near the
    body's guessed angle."""
    model = built.model
    data = model.createData()
    q_zero = np.zeros(model.nq)
    pin.computeJointJacobians(model, data, q_zero)
    pin.updateFramePlacements(model, data)
    q0 = built.q_guess()
    for body in scenario.bodies:
        fid = built.frame_id[Point(body.name)]
        rotation = data.oMf[fid].rotation
        row = frame_jacobian(model, data, fid)[5].copy()
        offset = math.atan2(rotation[1, 0], rotation[0, 0])
        turns = round((body.guess[2] - offset - float(row @ q0)) / (2.0 * math.pi))
        built.angle_row[body.name] = row
        built.angle_offset[body.name] = offset + 2.0 * math.pi * turns
