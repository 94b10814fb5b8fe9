"""The exact equivalent linkage of a disc cam, as an ordinary scenario.

A follower on a circular disc cam keeps a fixed relation to the disc's centre C, a point of the cam:
a knife-edge tip stays at distance R from C, a roller's centre at R + r, and a flat face at normal
distance R (the line through C parallel to the face slides along the follower). So the cam contact
is replaced by a light link: hinged at C on the cam and at the tip or roller centre on the follower
(knife edge, roller), or hinged at C and sliding without turning along the follower's face (flat
face). Every engine that builds joints builds this the same way: a like-for-like cam model.
Only eccentric discs have one; other profiles return None.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from scenarios.bodies import Body, Point
from scenarios.cam_profiles import EccentricDisc
from scenarios.cams import CamContact, FlatFaceCam, KnifeEdgeCam, RollerCam, follower_body
from scenarios.gears import GearPair, RackPinion
from scenarios.joints import Joint, Prismatic, Revolute
from scenarios.scenario import Scenario

LINK_MASS = 0.05
"""The link's mass as a fraction of the follower's: light (a kinematically driven result does not
depend on masses) but not massless, which MuJoCo's soft dynamics handle badly (2e-3 against 4e-10 on
the flat face at RK4, dt 1e-4)."""


def linkage_reason(scenario: Scenario) -> str | None:
    """Why the scenario's cams have no equivalent linkage, if they have none."""
    for contact in scenario.cams:
        if not isinstance(contact.profile, EccentricDisc):
            return f"cam '{contact.name}' is not a circular disc: it has no equivalent linkage"
    return None


def equivalent_linkage(scenario: Scenario) -> Scenario:
    """The scenario with every disc cam contact replaced by its equivalent link (ValueError when a
    profile has none). The links are extra bodies named `<contact>_link`, not outputs."""
    reason = linkage_reason(scenario)
    if reason:
        raise ValueError(reason)
    bodies: list[Body] = list(scenario.bodies)
    joints: list[Joint | GearPair | RackPinion | CamContact] = []
    for joint in scenario.joints:
        if isinstance(joint, KnifeEdgeCam | RollerCam | FlatFaceCam):
            link, rows = _link(scenario, joint)
            bodies.append(link)
            joints.extend(rows)
        else:
            joints.append(joint)
    return replace(
        scenario,
        bodies=tuple(bodies),
        joints=tuple(joints),
        outputs=scenario.output_bodies,
    )


def _centre(scenario: Scenario, contact: CamContact) -> tuple[Point, np.ndarray]:
    """The disc's centre C as a point of the cam, and its guessed world position."""
    disc = contact.profile
    assert isinstance(disc, EccentricDisc)
    x, y, theta = scenario.body(contact.cam).guess
    c, s = math.cos(theta), math.sin(theta)
    world = np.array([x + c * disc.eccentricity, y + s * disc.eccentricity])
    return Point(contact.cam, (disc.eccentricity, 0.0)), world


def _world(scenario: Scenario, p: Point) -> np.ndarray:
    x, y, theta = scenario.body(p.body).guess
    c, s = math.cos(theta), math.sin(theta)
    return np.array([x + c * p.local[0] - s * p.local[1], y + s * p.local[0] + c * p.local[1]])


def _link(scenario: Scenario, contact: CamContact) -> tuple[Body, list[Joint]]:
    disc = contact.profile
    assert isinstance(disc, EccentricDisc)
    centre, c_world = _centre(scenario, contact)
    name = f"{contact.name}_link"
    mass = LINK_MASS * scenario.body(follower_body(contact)).mass
    inertia = mass * disc.radius**2 / 12.0
    if isinstance(contact, FlatFaceCam):
        # the link keeps the follower's angle; its origin is C, sliding along the line parallel to
        # the face at distance R on the cam's side
        follower = scenario.body(contact.face.body)
        n = np.array(contact.normal, dtype=float)
        n /= np.linalg.norm(n)
        offset = np.array(contact.face.local) + disc.radius * n
        tangent = (-float(n[1]), float(n[0]))
        link = Body(
            name, (float(c_world[0]), float(c_world[1]), follower.guess[2]), mass=mass, inertia=inertia
        )
        rows: list[Joint] = [
            Revolute(f"{name}_hinge", Point(name), centre),
            Prismatic(
                f"{name}_slot",
                Point(contact.face.body, (float(offset[0]), float(offset[1]))),
                Point(name),
                axis=tangent,
            ),
        ]
        return link, rows
    tip = contact.tip if isinstance(contact, KnifeEdgeCam) else contact.centre
    length = disc.radius + (contact.roller_radius if isinstance(contact, RollerCam) else 0.0)
    direction = _world(scenario, tip) - c_world
    angle = math.atan2(float(direction[1]), float(direction[0]))
    link = Body(name, (float(c_world[0]), float(c_world[1]), angle), mass=mass, inertia=inertia)
    return link, [
        Revolute(f"{name}_hinge", Point(name), centre),
        Revolute(f"{name}_pin", Point(name, (length, 0.0)), tip),
    ]


CAM_MODELS = ("linkage", "contact")
"""The cam models an engine may offer: the equivalent linkage, or the cam contact itself."""


def default_cam_model(scenario: Scenario) -> str:
    """The same default in every engine: the equivalent linkage where the profile has one."""
    return "linkage" if scenario.cams and linkage_reason(scenario) is None else "contact"


def cam_model_scenario(scenario: Scenario, model: str) -> Scenario:
    """The scenario an engine builds for cam model `model` (ValueError for a linkage the profile
    does not allow, or an unknown model)."""
    if model not in CAM_MODELS:
        raise ValueError(f"cam_model must be one of {', '.join(CAM_MODELS)}, got '{model}'")
    return equivalent_linkage(scenario) if model == "linkage" and scenario.cams else scenario
