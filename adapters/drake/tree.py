"""What Drake's MultibodyPlant can hold of a scenario, planned in pure Python (no Drake).

The plant's joints are the mechanism's spanning tree (scenarios.topology): revolute joints about z
and prismatic joints in the plane, each joint frame aligned with its child's body frame so that a
revolute coordinate is the relative angle theta_child - theta_parent. The joints left over close
loops: a revolute as a ball constraint (SAP's point coincidence; the out-of-plane rows are satisfied
by the planar tree), a gear pair on a common carrier as a coupler constraint between two revolute
coordinates. Anything else has no faithful Drake form here and is refused with the reason.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from adapters.tree_edges import Coupling, Edge, coupling, tree_edges
from scenarios.bodies import GROUND
from scenarios.drivers import AbsoluteDriver
from scenarios.forces import AppliedForce, AppliedTorque, RotationalSpringDamper, SpringDamper
from scenarios.gears import GearPair, RackPinion
from scenarios.joints import Prismatic, Revolute
from scenarios.scenario import Scenario
from scenarios.topology import TopologyError, spanning_tree


class PlanError(ValueError):
    """The scenario has no faithful Drake model here; the message says why."""


@dataclass(frozen=True)
class Plan:
    edges: tuple[Edge, ...]
    balls: tuple[Revolute, ...]
    couplers: tuple[Coupling, ...]
    driver: AbsoluteDriver | None
    """The PD-driven coordinate; None in free dynamics, where only the loads move the bodies."""
    springs: tuple[SpringDamper, ...] = ()
    loads: tuple[AppliedTorque | AppliedForce, ...] = ()
    torsions: tuple[Torsion, ...] = ()


@dataclass(frozen=True)
class Torsion:
    """A torsion spring-damper on tree revolute joint `edge`: torque -k (q - q0) - c q_dot on its child."""

    edge: str
    stiffness: float
    damping: float
    q0: float


def _relative_angle(gear: GearPair, body: str, edges: tuple[Edge, ...]) -> tuple[str, float]:
    """(edge, sign) with rho = theta_body - theta_carrier = sign * q[edge]: the gear's own revolute
    joint on the carrier, or, for a ground gear, minus the carrier's revolute joint on the ground."""
    by_child = {e.child: e for e in edges}
    if body == GROUND:
        edge, sign = by_child.get(gear.carrier), -1.0
        on = GROUND
    else:
        edge, sign = by_child.get(body), 1.0
        on = gear.carrier
    if edge is None or edge.kind != "revolute" or edge.parent != on:
        raise PlanError(
            f"gear pair '{gear.name}': a coupler ties two revolute coordinates, and gear '{body}' "
            f"has no revolute joint giving its angle on carrier '{gear.carrier}'"
        )
    return edge.name, sign


def _coupler(gear: GearPair, edges: tuple[Edge, ...]) -> Coupling:
    """The gear law as q_j = ratio q_i + offset on the two joint coordinates that give the rho."""
    primary, secondary = (_relative_angle(gear, body, edges) for body in (gear.gear_i, gear.gear_j))
    return coupling(gear, primary, secondary)


def _torsion(force: RotationalSpringDamper, edges: tuple[Edge, ...]) -> Torsion:
    """The torsion spring on the tree's revolute joint between its two bodies (q = theta_child -
    theta_parent, so q0 is the free angle with the sign of that order)."""
    for edge in edges:
        if edge.kind == "revolute" and {edge.parent, edge.child} == {force.body_i, force.body_j}:
            sign = 1.0 if edge.child == force.body_j else -1.0
            return Torsion(edge.name, force.stiffness, force.damping, sign * force.free_angle)
    raise PlanError(
        f"torsion spring '{force.name}': Drake's RevoluteSpring acts on a revolute joint of the tree, "
        f"and '{force.body_i}' and '{force.body_j}' are joined by none"
    )


def _forces(
    scenario: Scenario, edges: tuple[Edge, ...]
) -> tuple[tuple[SpringDamper, ...], tuple[AppliedTorque | AppliedForce, ...], tuple[Torsion, ...]]:
    """The free-dynamics forces Drake holds: spring-dampers as its LinearSpringDamper (which needs a
    positive free length: its direction is undefined at zero length), applied loads, and torsion
    springs as RevoluteSpring with the joint's damping."""
    springs: list[SpringDamper] = []
    loads: list[AppliedTorque | AppliedForce] = []
    torsions: list[Torsion] = []
    for force in scenario.forces:
        if isinstance(force, SpringDamper):
            if force.free_length <= 0.0:
                raise PlanError(
                    f"spring '{force.name}': Drake's LinearSpringDamper needs a positive free length "
                    f"(it has {force.free_length:g})"
                )
            springs.append(force)
        elif isinstance(force, AppliedTorque | AppliedForce):
            loads.append(force)
        else:
            torsions.append(_torsion(force, edges))
    if len({t.edge for t in torsions}) < len(torsions):
        raise PlanError("two torsion springs on one joint: Drake's joint has one damping")
    return tuple(springs), tuple(loads), tuple(torsions)


def _driven_joint_first(scenario: Scenario) -> Scenario:
    """`scenario` with the driven body's joint on the ground listed first, so that the tree hangs
    that body from the ground (the PD drive acts on its joint); the same mechanism otherwise."""
    if len(scenario.drivers) != 1 or not isinstance(scenario.drivers[0], AbsoluteDriver):
        return scenario
    body = scenario.drivers[0].body
    grounded = [
        j
        for j in scenario.joints
        if isinstance(j, Revolute | Prismatic) and {j.p_i.body, j.p_j.body} == {GROUND, body}
    ]
    if not grounded:
        return scenario
    rest = tuple(j for j in scenario.joints if j is not grounded[0])
    return replace(scenario, joints=(grounded[0], *rest))


def plan(scenario: Scenario) -> Plan:
    """The plant's tree, constraints and drive; PlanError saying why the scenario has none."""
    if scenario.cams:
        raise PlanError("Drake has no cam joint, and a cam contact's profile is no constraint SAP offers")
    free = scenario.analysis == "dynamic"
    if free and scenario.drivers:
        raise PlanError("driven free dynamics (a PD drive beside the loads) is not modelled in Drake here")
    if not free and (len(scenario.drivers) != 1 or not isinstance(scenario.drivers[0], AbsoluteDriver)):
        raise PlanError("the Drake drive is one PD actuator on a joint: one absolute driver is modelled")
    try:
        spanning = spanning_tree(_driven_joint_first(scenario))
    except TopologyError as error:
        raise PlanError(f"{error}, so they have no place in Drake's joint tree") from None
    edges = tree_edges(scenario, spanning, PlanError)
    named = {j.name: j for j in scenario.joints}
    balls: list[Revolute] = []
    couplers: list[Coupling] = []
    for name in spanning.closures:
        joint = named[name]
        if isinstance(joint, Revolute):
            balls.append(joint)
        elif isinstance(joint, GearPair):
            couplers.append(_coupler(joint, edges))
        elif isinstance(joint, RackPinion):
            raise PlanError(
                f"rack and pinion '{name}': Drake's coupler ties two joint coordinates of one kind"
            )
        else:
            raise PlanError(
                f"loop-closing joint '{name}' ({type(joint).__name__}) has no SAP constraint here"
            )
    if free:
        return Plan(edges, tuple(balls), tuple(couplers), None, *_forces(scenario, edges))
    driver = scenario.drivers[0]
    assert isinstance(driver, AbsoluteDriver)
    edge = next(e for e in edges if e.child == driver.body)
    if edge.parent != GROUND or edge.kind == "fixed":
        raise PlanError(f"driver '{driver.name}': the PD drive needs the driven body's joint on the ground")
    if (edge.kind == "revolute") != (driver.coordinate == "theta"):
        raise PlanError(f"driver '{driver.name}' drives {driver.coordinate}, not its joint's coordinate")
    return Plan(edges, tuple(balls), tuple(couplers), driver)
