"""The kinematic tree Pinocchio needs, planned from a scenario's joints (pure Python, no Pinocchio).

The tree is the mechanism's spanning tree (scenarios.topology). Every other joint, gear and cam
contact stays a loop-closure row, except gear pairs that can be Pinocchio mimic joints.

Every joint frame is aligned with its child's body frame, so a revolute coordinate is exactly the
relative angle theta_child - theta_parent, as the gear law needs for a mimic joint.
"""

from __future__ import annotations

from dataclasses import dataclass

from adapters.tree_edges import Coordinate, Coupling, Edge, coupling, tree_edges
from scenarios.bodies import GROUND, Point, Pose
from scenarios.gears import GearPair
from scenarios.geometry import compose
from scenarios.scenario import Scenario
from scenarios.topology import TopologyError, spanning_tree


class TreeError(ValueError):
    """The scenario's joints do not make a tree Pinocchio can hold; the message says why."""


@dataclass(frozen=True)
class Tree:
    edges: tuple[Edge, ...]
    """Parents before children."""
    closures: tuple[str, ...]
    """Names of the scenario's joints, gears and cam contacts left as loop-closure rows."""
    mimics: tuple[Coupling, ...] = ()

    def edge_of(self, body: str) -> Edge:
        """The edge whose child is `body`."""
        return next(e for e in self.edges if e.child == body)


def plan(scenario: Scenario, mimic_gears: bool = True) -> Tree:
    """Pinocchio's tree on the mechanism's spanning tree (scenarios.topology); TreeError if a body
    cannot be reached by a tree joint."""
    try:
        spanning = spanning_tree(scenario)
    except TopologyError as error:
        raise TreeError(f"{error}, so they have no place in Pinocchio's kinematic tree") from None
    edges = tree_edges(scenario, spanning, TreeError)
    tree = Tree(edges, spanning.closures)
    return _with_mimics(scenario, tree) if mimic_gears else tree


def _relative_coordinate(tree: Tree, gear: str, carrier: str) -> Coordinate | None:
    """(edge, sign) with theta_gear - theta_carrier = sign * q[edge], if one revolute edge gives it."""
    for e in tree.edges:
        if e.kind == "revolute" and (e.parent, e.child) == (carrier, gear):
            return e.name, 1.0
        if e.kind == "revolute" and (e.parent, e.child) == (gear, carrier):
            return e.name, -1.0
    return None


def _with_mimics(scenario: Scenario, tree: Tree) -> Tree:
    """Turn gear pairs into mimic joints where the gear law ties two single revolute coordinates.

    The secondary is gear j's coordinate if it gives rho_j with a plus sign, else gear i's if that
    one does; a pair whose coordinates both give minus rho stays a loop closure.
    """
    mimics: list[Coupling] = []
    closures = list(tree.closures)
    taken: set[str] = set()
    for gear in (j for j in scenario.joints if isinstance(j, GearPair)):
        ci = _relative_coordinate(tree, gear.gear_i, gear.carrier)
        cj = _relative_coordinate(tree, gear.gear_j, gear.carrier)
        if ci is None or cj is None or ci[0] == cj[0] or {ci[0], cj[0]} & taken:
            continue
        if cj[1] < 0 and ci[1] < 0:  # a mimic's secondary must give its gear's rho with a plus sign
            continue
        mimic = coupling(gear, ci, cj, solve_for_i=cj[1] < 0)
        mimics.append(mimic)
        taken |= {mimic.secondary, mimic.primary}
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
