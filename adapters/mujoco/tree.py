"""The kinematic tree MuJoCo needs, planned from a scenario's joints (no MuJoCo here).

The mechanism's spanning tree (scenarios.topology) becomes MuJoCo's body tree; every revolute left
over becomes a loop closure (a `connect`), and any other joint left over cannot be closed. Each body
is authored at a pose that satisfies its tree joint exactly, so qpos = 0 is a valid tree
configuration and only the loop closures carry the authoring gap. Angles and, where the tree allows,
points are affine in qpos: that is what lets gears, racks and drivers become MuJoCo's linear joint
and tendon equalities.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np

from scenarios.bodies import GROUND, Point, Pose, Vec2
from scenarios.geometry import world_point
from scenarios.joints import Ground, Prismatic, Revolute
from scenarios.scenario import Scenario
from scenarios.topology import GROWTH_ORDER, TopologyError, ends, spanning_tree


class TreeError(ValueError):
    """The scenario's joints cannot be arranged as a MuJoCo tree; the message says why."""


@dataclass(frozen=True)
class TreeJoint:
    """The joint that attaches `child` to `parent`: a z hinge at `anchor` or a slide along `axis`
    (both in the child's frame); `fixed` welds the child to the parent."""

    name: str
    kind: Literal["hinge", "slide", "fixed"]
    parent: str
    child: str
    anchor: Vec2 = (0.0, 0.0)
    axis: Vec2 = (1.0, 0.0)


@dataclass(frozen=True)
class Tree:
    """Tree joints in parent-before-child order, the revolutes left to close loops, and the world
    pose of every body at qpos = 0."""

    joints: tuple[TreeJoint, ...]
    closures: tuple[Revolute, ...]
    poses: dict[str, Pose]

    def joint_of(self, body: str) -> TreeJoint:
        return next(j for j in self.joints if j.child == body)

    def path(self, body: str) -> list[TreeJoint]:
        """Tree joints from the ground down to `body`."""
        chain: list[TreeJoint] = []
        while body != GROUND:
            joint = self.joint_of(body)
            chain.append(joint)
            body = joint.parent
        return chain[::-1]

    def point(self, p: Point) -> np.ndarray:
        """World position of `p` at qpos = 0."""
        return _world(p, self.poses)


@dataclass(frozen=True)
class Affine:
    """value = const + sum(coefs[joint] * qpos[joint])."""

    const: float
    coefs: dict[str, float]

    def __add__(self, other: Affine) -> Affine:
        coefs = dict(self.coefs)
        for joint, c in other.coefs.items():
            coefs[joint] = coefs.get(joint, 0.0) + c
        return Affine(self.const + other.const, coefs)

    def scaled(self, factor: float) -> Affine:
        return Affine(self.const * factor, {j: c * factor for j, c in self.coefs.items()})


def rot(theta: float) -> np.ndarray:
    c, s = math.cos(theta), math.sin(theta)
    return np.array([[c, -s], [s, c]])


def plan_tree(scenario: Scenario, poses: dict[str, Pose] | None = None) -> Tree:
    """Spanning tree of `scenario`, authored near `poses` (the bodies' guesses by default)."""
    guess = poses or {b.name: b.guess for b in scenario.bodies}
    try:
        spanning = spanning_tree(scenario)
    except TopologyError as error:
        raise TreeError(str(error)) from None
    by_name = {joint.name: joint for joint in scenario.joints}
    order = {name: k for k, name in enumerate(by_name)}
    chosen = sorted(
        (e.joint for e in spanning.edges), key=lambda j: (GROWTH_ORDER.index(type(j)), order[j.name])
    )
    closures = []
    for name in spanning.closures:
        joint = by_name[name]
        if isinstance(joint, Revolute):
            closures.append(joint)
        elif isinstance(joint, Ground | Prismatic):
            raise TreeError(f"joint '{joint.name}' closes a loop, and MuJoCo closes loops only at pins")
    placed: dict[str, Pose] = {GROUND: (0.0, 0.0, 0.0)}
    ordered: list[TreeJoint] = []
    frontier = [GROUND]
    while frontier:
        parent = frontier.pop(0)
        for joint in chosen:
            a, b = ends(joint)
            if parent in (a, b) and (b if parent == a else a) not in placed:
                child = b if parent == a else a
                tree_joint, pose = _attach(joint, parent, child, placed, guess)
                placed[child] = pose
                ordered.append(tree_joint)
                frontier.append(child)
    del placed[GROUND]
    return Tree(tuple(ordered), tuple(closures), placed)


def _world(p: Point, placed: dict[str, Pose]) -> np.ndarray:
    if p.body == GROUND:
        return np.array(p.local, dtype=float)
    return np.array(world_point(placed[p.body], p.local))


def _attach(
    joint: Ground | Prismatic | Revolute,
    parent: str,
    child: str,
    placed: dict[str, Pose],
    guess: dict[str, Pose],
) -> tuple[TreeJoint, Pose]:
    """The tree joint for `child` and the child's pose that satisfies it exactly."""
    if isinstance(joint, Ground):
        return TreeJoint(joint.name, "fixed", GROUND, child), joint.pose
    theta_parent = placed[parent][2]
    own, other = (joint.p_i, joint.p_j) if joint.p_i.body == child else (joint.p_j, joint.p_i)
    anchor = np.array(_world(other, placed))
    local = np.array(own.local, dtype=float)
    if isinstance(joint, Revolute):
        theta = guess[child][2]
        origin = anchor - rot(theta) @ local
        return TreeJoint(joint.name, "hinge", parent, child, own.local), (*origin, theta)
    child_is_i = joint.p_i.body == child
    theta = theta_parent + joint.angle if child_is_i else theta_parent - joint.angle
    theta_i = theta if child_is_i else theta_parent
    axis_world = rot(theta_i) @ np.array(joint.axis, dtype=float)
    axis_world /= np.linalg.norm(axis_world)
    gx, gy, gth = guess[child]
    guess_point = np.array([gx, gy]) + rot(gth) @ local
    travel = float(axis_world @ (guess_point - anchor))
    origin = anchor + travel * axis_world - rot(theta) @ local
    axis_local = rot(theta).T @ axis_world
    return (
        TreeJoint(joint.name, "slide", parent, child, own.local, (axis_local[0], axis_local[1])),
        (*origin, theta),
    )


def angle(tree: Tree, body: str) -> Affine:
    """The body's absolute angle, affine in the hinges above it."""
    if body == GROUND:
        return Affine(0.0, {})
    hinges = {j.name: 1.0 for j in tree.path(body) if j.kind == "hinge"}
    return Affine(tree.poses[body][2], hinges)


def position(tree: Tree, p: Point) -> tuple[Affine, Affine] | None:
    """(x, y) of point p, or None where it is not affine in qpos: every joint above p must be a slide,
    except p's own body's joint, which may be a hinge at p."""
    base = tree.point(p)
    if p.body == GROUND:
        return Affine(base[0], {}), Affine(base[1], {})
    path = tree.path(p.body)
    *upper, own = path
    if any(j.kind == "hinge" for j in upper):
        return None
    if own.kind == "hinge" and not np.allclose(own.anchor, p.local, rtol=0.0, atol=1e-12):
        return None
    cx: dict[str, float] = {}
    cy: dict[str, float] = {}
    for j in path:
        if j.kind == "slide":
            axis = rot(tree.poses[j.child][2]) @ np.array(j.axis)
            cx[j.name], cy[j.name] = float(axis[0]), float(axis[1])
    return Affine(float(base[0]), cx), Affine(float(base[1]), cy)
