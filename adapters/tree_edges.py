"""A mechanism's spanning tree as an engine's tree joints, planned in pure Python (no engine here).

The tree is the mechanism's spanning tree (scenarios.topology). Every joint frame is aligned with
its child's body frame, so that a revolute coordinate is exactly the relative angle theta_child -
theta_parent; a prismatic joint's frame is turned on the parent by the joint's constant angle, its
axis a unit vector in that frame. A gear pair on two such revolute coordinates is one linear law
between them (`Coupling`). The engines whose trees are built this way (their joint frames, and
their mimic joints or coupler constraints) share this plan, so that their trees agree.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Literal

from scenarios.bodies import GROUND, Pose, Vec2
from scenarios.gears import GearPair
from scenarios.geometry import compose, rotate
from scenarios.joints import Ground, Prismatic, Revolute
from scenarios.scenario import Scenario
from scenarios.topology import SpanningTree

EdgeKind = Literal["revolute", "prismatic", "fixed"]
Coordinate = tuple[str, float]
"""(edge, sign): an angle that is sign * q[edge]."""


@dataclass(frozen=True)
class Edge:
    """Tree joint `name` hangs body `child` from `parent` (a body or the ground).

    `parent_frame` is the joint frame in the parent's body frame, `child_pose` the child's body frame
    in the joint frame; `axis` the prismatic direction in the joint frame; `q0` a first guess of the
    coordinate from the bodies' guessed poses."""

    name: str
    kind: EdgeKind
    parent: str
    child: str
    parent_frame: Pose
    child_pose: Pose
    axis: Vec2 = (1.0, 0.0)
    q0: float = 0.0

    @property
    def child_frame(self) -> Pose:
        """The joint frame in the child's body frame (the inverse of `child_pose`)."""
        x, y, theta = self.child_pose
        back = rotate(-theta, (-x, -y))
        return (back[0], back[1], -theta)


@dataclass(frozen=True)
class Coupling:
    """Gear pair `gear` as q[secondary] = ratio * q[primary] + offset on two revolute edges."""

    gear: str
    primary: str
    secondary: str
    ratio: float
    offset: float


def _guess(scenario: Scenario, body: str) -> Pose:
    return (0.0, 0.0, 0.0) if body == GROUND else scenario.body(body).guess


def _edge(
    scenario: Scenario, joint: Ground | Prismatic | Revolute, parent: str, error: Callable[[str], Exception]
) -> Edge:
    if isinstance(joint, Ground):
        return Edge(joint.name, "fixed", GROUND, joint.body, (0.0, 0.0, 0.0), joint.pose)
    p_parent, p_child = (joint.p_i, joint.p_j) if joint.p_i.body == parent else (joint.p_j, joint.p_i)
    parent_guess, child_guess = _guess(scenario, parent), _guess(scenario, p_child.body)
    child_pose = (-p_child.local[0], -p_child.local[1], 0.0)
    if isinstance(joint, Revolute):
        q0 = child_guess[2] - parent_guess[2]
        return Edge(joint.name, "revolute", parent, p_child.body, (*p_parent.local, 0.0), child_pose, q0=q0)
    # theta_i - theta_j = angle, the axis given in body i's frame
    child_is_i = p_child is joint.p_i
    turn = joint.angle if child_is_i else -joint.angle
    axis = joint.axis if child_is_i else rotate(joint.angle, joint.axis)
    norm = math.hypot(*axis)
    if norm == 0.0:
        raise error(f"prismatic joint '{joint.name}' has a zero axis")
    axis = (axis[0] / norm, axis[1] / norm)
    frame = compose(parent_guess, (*p_parent.local, turn))
    start = compose(child_guess, (*p_child.local, 0.0))
    world_axis = rotate(frame[2], axis)
    q0 = (start[0] - frame[0]) * world_axis[0] + (start[1] - frame[1]) * world_axis[1]
    return Edge(joint.name, "prismatic", parent, p_child.body, (*p_parent.local, turn), child_pose, axis, q0)


def tree_edges(
    scenario: Scenario, spanning: SpanningTree, error: Callable[[str], Exception]
) -> tuple[Edge, ...]:
    """The spanning tree's edges as tree joints, parents before children; `error(message)` is raised
    for a joint no tree can hold (a prismatic joint with a zero axis)."""
    return tuple(_edge(scenario, e.joint, e.parent, error) for e in spanning.edges)


def coupling(
    gear: GearPair, coordinate_i: Coordinate, coordinate_j: Coordinate, solve_for_i: bool = False
) -> Coupling:
    """The gear law r_i rho_i + s r_j rho_j = c (rho = theta - theta_carrier, s = -1 inside) as a law
    of one gear's edge on the other's (gear j's on gear i's, or i's on j's if `solve_for_i`), given
    each gear's (edge, sign) with rho = sign * q[edge]."""
    (edge_i, sign_i), (edge_j, sign_j) = coordinate_i, coordinate_j
    s = -1.0 if gear.internal else 1.0
    c = gear.radius_i * (gear.theta0_i - gear.theta0_carrier) + s * gear.radius_j * (
        gear.theta0_j - gear.theta0_carrier
    )
    a_i, a_j = gear.radius_i * sign_i, s * gear.radius_j * sign_j
    if solve_for_i:
        return Coupling(gear.name, edge_j, edge_i, -a_j / a_i, c / a_i)
    return Coupling(gear.name, edge_i, edge_j, -a_i / a_j, c / a_j)
