"""The kinematic tree Pinocchio needs, planned from a scenario's joints (pure Python, no Pinocchio).

The tree is the mechanism's spanning tree (scenarios.topology). Every other joint, gear and cam
contact stays a loop-closure row, except gear pairs that can be Pinocchio mimic joints.

Every joint frame is aligned with its child's body frame, so a revolute coordinate is exactly the
relative angle theta_child - theta_parent, as the gear law needs for a mimic joint.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

from scenarios.bodies import GROUND, Point, Pose, Vec2
from scenarios.gears import GearPair
from scenarios.geometry import compose, rotate
from scenarios.joints import Ground, Prismatic, Revolute
from scenarios.scenario import Scenario
from scenarios.topology import TopologyError, spanning_tree

EdgeKind = Literal["revolute", "prismatic", "fixed"]


class TreeError(ValueError):
    """The scenario's joints do not make a tree Pinocchio can hold; the message says why."""


@dataclass(frozen=True)
class Edge:
    """One tree joint: `child` hangs from `parent` (a body or the ground) through scenario joint `name`.

    `placement` is the joint frame in the parent's body frame, `axis` the prismatic direction in the
    joint frame, `child_pose` the child's body frame in the joint frame, `q0` a first guess of the
    joint coordinate from the bodies' rough guesses.
    """

    name: str
    kind: EdgeKind
    parent: str
    child: str
    placement: Pose
    axis: Vec2 = (1.0, 0.0)
    child_pose: Pose = (0.0, 0.0, 0.0)
    q0: float = 0.0


@dataclass(frozen=True)
class Mimic:
    """Gear pair `gear` as a mimic joint: q[secondary] = scaling * q[primary] + offset (edge names)."""

    gear: str
    secondary: str
    primary: str
    scaling: float
    offset: float


@dataclass(frozen=True)
class Tree:
    edges: tuple[Edge, ...]
    """Parents before children."""
    closures: tuple[str, ...]
    """Names of the scenario's joints, gears and cam contacts left as loop-closure rows."""
    mimics: tuple[Mimic, ...] = ()

    def edge_of(self, body: str) -> Edge:
        """The edge whose child is `body`."""
        return next(e for e in self.edges if e.child == body)


def _guess(scenario: Scenario, body: str) -> Pose:
    return (0.0, 0.0, 0.0) if body == GROUND else scenario.body(body).guess


def _edge(scenario: Scenario, joint: Ground | Prismatic | Revolute, parent: str) -> Edge:
    if isinstance(joint, Ground):
        return Edge(joint.name, "fixed", GROUND, joint.body, (0.0, 0.0, 0.0), child_pose=joint.pose)
    p_parent, p_child = (joint.p_i, joint.p_j) if joint.p_i.body == parent else (joint.p_j, joint.p_i)
    parent_guess, child_guess = _guess(scenario, parent), _guess(scenario, p_child.body)
    offset = (-p_child.local[0], -p_child.local[1], 0.0)
    if isinstance(joint, Revolute):
        place = (*p_parent.local, 0.0)
        return Edge(
            joint.name,
            "revolute",
            parent,
            p_child.body,
            place,
            (1.0, 0.0),
            offset,
            child_guess[2] - parent_guess[2],
        )
    # Prismatic: theta_i - theta_j = angle; the axis is given in body i's frame.
    child_is_i = p_child is joint.p_i
    turn = joint.angle if child_is_i else -joint.angle
    axis = joint.axis if child_is_i else rotate(joint.angle, joint.axis)
    norm = math.hypot(*axis)
    if norm == 0.0:
        raise TreeError(f"prismatic joint '{joint.name}' has a zero axis")
    axis = (axis[0] / norm, axis[1] / norm)
    frame = compose(parent_guess, (*p_parent.local, turn))
    start = compose(child_guess, (*p_child.local, 0.0))
    world_axis = rotate(frame[2], axis)
    q0 = (start[0] - frame[0]) * world_axis[0] + (start[1] - frame[1]) * world_axis[1]
    return Edge(joint.name, "prismatic", parent, p_child.body, (*p_parent.local, turn), axis, offset, q0)


def plan(scenario: Scenario, mimic_gears: bool = True) -> Tree:
    """Pinocchio's tree on the mechanism's spanning tree (scenarios.topology); TreeError if a body
    cannot be reached by a tree joint."""
    try:
        spanning = spanning_tree(scenario)
    except TopologyError as error:
        raise TreeError(f"{error}, so they have no place in Pinocchio's kinematic tree") from None
    edges = tuple(_edge(scenario, e.joint, e.parent) for e in spanning.edges)
    tree = Tree(edges, spanning.closures)
    return _with_mimics(scenario, tree) if mimic_gears else tree


def _relative_coordinate(tree: Tree, gear: str, carrier: str) -> tuple[str, float] | None:
    """(edge, sign) with theta_gear - theta_carrier = sign * q[edge], if one revolute edge gives it."""
    for e in tree.edges:
        if e.kind == "revolute" and (e.parent, e.child) == (carrier, gear):
            return e.name, 1.0
        if e.kind == "revolute" and (e.parent, e.child) == (gear, carrier):
            return e.name, -1.0
    return None


def _with_mimics(scenario: Scenario, tree: Tree) -> Tree:
    """Turn gear pairs into mimic joints where the gear law ties two single revolute coordinates.

    With rho = theta - theta_carrier, the gear law is r_i rho_i + s r_j rho_j = c (s = -1 inside).
    """
    mimics: list[Mimic] = []
    closures = list(tree.closures)
    taken: set[str] = set()
    for gear in (j for j in scenario.joints if isinstance(j, GearPair)):
        s = -1.0 if gear.internal else 1.0
        ci = _relative_coordinate(tree, gear.gear_i, gear.carrier)
        cj = _relative_coordinate(tree, gear.gear_j, gear.carrier)
        if ci is None or cj is None or ci[0] == cj[0] or {ci[0], cj[0]} & taken:
            continue
        c = gear.radius_i * (gear.theta0_i - gear.theta0_carrier) + s * gear.radius_j * (
            gear.theta0_j - gear.theta0_carrier
        )
        terms = [(cj, s * gear.radius_j), (ci, gear.radius_i)]
        secondary = next(((co, k) for co, k in terms if co[1] > 0), None)
        if secondary is None:
            continue
        (sec, _), k_sec = secondary
        (pri, sign_p), k_pri = next(t for t in terms if t[0][0] != sec)
        mimics.append(Mimic(gear.name, sec, pri, -k_pri * sign_p / k_sec, c / k_sec))
        taken |= {sec, pri}
        closures.remove(gear.name)
    return Tree(tree.edges, tuple(closures), tuple(mimics))


def body_pose(tree: Tree, body: str) -> tuple[str, Pose]:
    """(name of the edge whose joint carries `body`, or GROUND, and the body frame's pose in it)."""
    if body == GROUND:
        return GROUND, (0.0, 0.0, 0.0)
    edge = tree.edge_of(body)
    if edge.kind != "fixed":
        return edge.name, edge.child_pose
    carrier, pose = body_pose(tree, edge.parent)
    return carrier, compose(pose, edge.child_pose)


def point_pose(tree: Tree, point: Point) -> tuple[str, Pose]:
    """(carrying edge or GROUND, the point's pose in that joint frame, aligned with the body)."""
    carrier, pose = body_pose(tree, point.body)
    return carrier, compose(pose, (*point.local, 0.0))
