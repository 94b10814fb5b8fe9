"""Gravity and the force elements of a dynamic scenario as Exudyn's own loads and connectors.

Gravity is a `LoadMassProportional` on each body; an applied torque a `LoadTorqueVector` on the body
(and minus it on its reaction body); an applied force a `LoadForceVector` in global axes at the body
point; a spring-damper Exudyn's `ObjectConnectorSpringDamper` between the two points; a rotational
spring-damper on a revolute pair a `ObjectConnectorCoordinateSpringDamper` on the two bodies'
rotation coordinates (exact for continuous angles: Exudyn's rotational spring-damper measures the
angle from the relative rotation matrix, which wraps). Magnitudes that vary in time are load user
functions of the motion law; constant ones are plain load vectors, evaluated inside Exudyn.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from exudyn.itemInterface import (
    LoadForceVector,
    LoadMassProportional,
    LoadTorqueVector,
    MarkerBodyMass,
    MarkerBodyRigid,
    MarkerNodeCoordinate,
    ObjectConnectorCoordinateSpringDamper,
    ObjectConnectorSpringDamper,
)

from scenarios.bodies import GROUND, Point
from scenarios.forces import AppliedForce, AppliedTorque, RotationalSpringDamper, SpringDamper
from scenarios.motions import Constant, Motion
from scenarios.scenario import Scenario

FORCES = (AppliedTorque, AppliedForce, SpringDamper, RotationalSpringDamper)


def add_loads(
    mbs: Any,
    scenario: Scenario,
    objects: dict[str, Any],
    nodes: dict[str, Any],
    at: Callable[[Point], Any],
    ground_coordinate: Any,
) -> None:
    """Gravity on every body and every force element of `scenario`; `objects` and `nodes` by body
    name, `at` a position marker at a body point, `ground_coordinate` a coordinate marker on ground."""
    gx, gy = (float(g) for g in scenario.gravity)
    if gx or gy:
        for body in scenario.bodies:
            marker = mbs.AddMarker(MarkerBodyMass(bodyNumber=objects[body.name]))
            mbs.AddLoad(LoadMassProportional(markerNumber=marker, loadVector=[gx, gy, 0.0]))

    def rotation(body: str) -> Any:
        if body == GROUND:
            return ground_coordinate
        return mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=nodes[body], coordinate=2))

    for force in scenario.forces:
        if isinstance(force, AppliedTorque):
            for name, sign in ((force.body, 1.0), (force.reaction, -1.0)):
                if name != GROUND:
                    marker = mbs.AddMarker(MarkerBodyRigid(bodyNumber=objects[name], localPosition=[0.0] * 3))
                    torque = _vector((None, None, force.torque), sign)
                    mbs.AddLoad(LoadTorqueVector(markerNumber=marker, **torque))
        elif isinstance(force, AppliedForce):
            if force.point.body != GROUND:
                vector = _vector((force.fx, force.fy, None), 1.0)
                mbs.AddLoad(LoadForceVector(markerNumber=at(force.point), bodyFixed=False, **vector))
        elif isinstance(force, SpringDamper):
            markers = [at(force.p_i), at(force.p_j)]
            law: dict[str, Any] = {"stiffness": force.stiffness, "damping": force.damping}
            mbs.AddObject(
                ObjectConnectorSpringDamper(markerNumbers=markers, referenceLength=force.free_length, **law)
            )
        elif isinstance(force, RotationalSpringDamper):
            # Exudyn's coordinate spring-damper: f = k (q1 - q0 - offset) + d (q1' - q0'), +f on
            # marker 0's coordinate and -f on marker 1's: the scenario's torque on body i and j
            markers = [rotation(force.body_i), rotation(force.body_j)]
            law = {"stiffness": force.stiffness, "damping": force.damping}
            mbs.AddObject(
                ObjectConnectorCoordinateSpringDamper(markerNumbers=markers, offset=force.free_angle, **law)
            )
        else:
            raise TypeError(f"no Exudyn element for {type(force).__name__}")


def _vector(laws: tuple[Motion | None, Motion | None, Motion | None], sign: float) -> dict[str, Any]:
    """Exudyn's load arguments for the vector sign * (laws(t)) (None: zero): a constant load vector,
    or a load vector user function of time."""
    if all(law is None or isinstance(law, Constant) for law in laws):
        return {"loadVector": [0.0 if law is None else sign * law.f(0.0) for law in laws]}

    def load(mbs: Any, t: float, load_vector: Any) -> list[float]:
        return [0.0 if law is None else sign * law.f(t) for law in laws]

    return {"loadVector": [0.0, 0.0, 0.0], "loadVectorUserFunction": load}
