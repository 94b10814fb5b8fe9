"""A mechanism's topology: a spanning tree of its joints grown from the ground, and the joints left
over to close loops. Engine-neutral; every engine that needs a kinematic tree (MuJoCo, Pinocchio)
builds its own from this one plan.

The tree grows from the ground one joint at a time, each time taking the first joint, in the
scenario's order, that reaches a body not yet placed, preferring ground (fixed) joints, then
prismatic, then revolute ones: so the joints left to close loops are revolutes where possible.
Every other joint, gear, rack and cam contact closes a loop.
"""

from __future__ import annotations

from dataclasses import dataclass

from scenarios.bodies import GROUND
from scenarios.joints import Ground, Prismatic, Revolute
from scenarios.scenario import Scenario

TreeJointKind = Ground | Prismatic | Revolute
GROWTH_ORDER: tuple[type, ...] = (Ground, Prismatic, Revolute)


class TopologyError(ValueError):
    """Some bodies cannot be reached from the ground through tree joints; the message names them."""


@dataclass(frozen=True)
class TreeEdge:
    """Scenario joint `joint` hangs body `child` from `parent` (a body or the ground)."""

    joint: TreeJointKind
    parent: str
    child: str


@dataclass(frozen=True)
class SpanningTree:
    edges: tuple[TreeEdge, ...]
    """In growth order: every parent before its children."""
    closures: tuple[str, ...]
    """Names of the scenario's joints, gears and cam contacts that close loops, in scenario order."""

    def edge_of(self, body: str) -> TreeEdge:
        """The edge whose child is `body`."""
        return next(e for e in self.edges if e.child == body)


def ends(joint: TreeJointKind) -> tuple[str, str]:
    """The two bodies a tree joint connects."""
    return (GROUND, joint.body) if isinstance(joint, Ground) else (joint.p_i.body, joint.p_j.body)


def spanning_tree(scenario: Scenario) -> SpanningTree:
    """The spanning tree of `scenario`; TopologyError if a body cannot be reached from the ground."""
    placed = {GROUND}
    edges: list[TreeEdge] = []
    while True:
        for kind in GROWTH_ORDER:
            joint = next(
                (
                    j
                    for j in scenario.joints
                    if isinstance(j, kind) and sum(b in placed for b in ends(j)) == 1  # type: ignore[arg-type]
                ),
                None,
            )
            if joint is not None:
                a, b = ends(joint)  # type: ignore[arg-type]
                parent, child = (a, b) if a in placed else (b, a)
                edges.append(TreeEdge(joint, parent, child))  # type: ignore[arg-type]
                placed.add(child)
                break
        else:
            break
    missing = [b for b in scenario.body_names if b not in placed]
    if missing:
        raise TopologyError(
            f"bodies {', '.join(missing)} are not reached from the ground "
            "by revolute, prismatic or ground joints"
        )
    used = {e.joint.name for e in edges}
    return SpanningTree(tuple(edges), tuple(j.name for j in scenario.joints if j.name not in used))
