"""Cam contacts as MuJoCo contact geometry (no MuJoCo here).

MuJoCo has no cam joint: the cam is real geometry and the follower is held on it by a preloaded
spring, through a frictionless contact pair. The eccentric disc is a capsule whose axis is normal to
the plane (its section in the plane is exactly the disc, and MuJoCo's capsule colliders are
analytic); the roller is a sphere, the flat face the face of a box, the knife edge the edge of a box
turned 45 degrees about its point. Any other profile (a spline, a lobed cam) is a polygon of
`cam_pieces` facets, thin capsules lying in the plane whose outer sides are the chords between
profile points at equal angles (adapters.mujoco.cam_facets), one contact pair per facet: every
collision stays analytic (capsule-sphere, capsule-box, as on the disc), the follower rides the chords
(a sagitta of kappa c^2 / 8), and its velocity and acceleration carry the facets' kinks, smoothed by
the soft contact (measured errors in cam_facets.DEFAULT_PIECES). A knife edge on such a polygon
would chatter (its velocity jumps at every vertex): it is a sphere centred on its tip rolling on the
facets of the profile's inward offset by the sphere's radius, whose centre traces the knife's path
exactly (adapters.mujoco.cam_tip). A lobed cam is refused (its follower chatters; concave valleys
the follower cannot follow are named: cam_facets.lobed_reason): spline profiles are built as facets.

A flat face on facets collides through a contype/conaffinity bit of its own instead of one explicit
pair per facet (CamPair.mask): MuJoCo filters an explicit pair by bounding spheres alone, and the
face's box, four cam radii long, has a sphere that holds the whole cam, so the box-capsule collider
ran on every facet at every collision; by bits a collision costs a fraction of that, and the
trajectories are the same to the bit.
Colliding by bits, the pairs go through MuJoCo's mid-phase, which prunes on the oriented boxes of the
cam body's bounding-volume tree and of each geom, boxes that contain their geoms: the facets it
drops cannot touch the face, so the contacts are the same ones, from the same collider on the same
two geoms in the same order, with the same parameters (the two geoms carry the pair's condim, solref
and solimp, which MuJoCo's mix of equal values leaves as they are). A sphere follower (a roller, a
knife edge's tip on facets) keeps its explicit pairs: its small bounding sphere drops nearly every
facet already, and cheaper than the broad phase's pass over the cam's hundreds of geoms.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from adapters.mujoco.cam_facets import DEFAULT_PIECES, extent, facets, lobed_reason
from adapters.mujoco.cam_tip import tip_radius, tip_reason
from adapters.mujoco.tree import Tree, TreeError, rot
from scenarios.bodies import Point
from scenarios.cam_profiles import EccentricDisc, LobedProfile, SplineProfile
from scenarios.cams import CamContact, FlatFaceCam, KnifeEdgeCam, RollerCam

LOBES_ON_FACETS = (
    "MuJoCo's model of it is a polygon of facets, on which the follower is thrown off the vertices "
    "and chatters (measured on cam_roller with profile=lobed: acceleration 501 m/s^2, the preload "
    "over the mass, against 36 m/s^2, at 512 and 2048 facets alike; the knife edge with profile=lobed, a "
    "sphere on the profile's offset, 501 m/s^2 alike)"
)
HALF_HEIGHT = 0.2
"""Half-thickness of all cam geometry normal to the plane, in cam disc radii."""
MASK_BITS = 31
"""contype/conaffinity bits a cam may collide by (MuJoCo's are 32-bit ints; the sign bit unused):
the cam at index k in the scenario's cams takes bit k, so a flat face on facets past the 31st cam
keeps its explicit pairs."""


@dataclass(frozen=True)
class Geom:
    """One geom: the body it sits on and its MJCF attributes (name, type, size, pos, quat)."""

    body: str
    name: str
    kind: str
    size: tuple[float, ...]
    pos: tuple[float, float] = (0.0, 0.0)
    angle: float = 0.0
    fromto: tuple[float, float, float, float] | None = None
    """A capsule lying in the plane from (x1, y1) to (x2, y2), instead of pos and angle."""


@dataclass(frozen=True)
class CamPair:
    """The geoms of one cam contact (the cam's: one capsule, or its facets) and the follower joint
    that carries the preload spring."""

    name: str
    cam: tuple[Geom, ...]
    follower: Geom
    spring_joint: str
    mask: int = 0
    """The contype bit of the cam's geoms and conaffinity bit of its follower, 1 << (the cam's index
    among the scenario's cams), where they collide by bits (a flat face on facets); 0: one explicit
    contact pair per cam geom."""


def unsupported_reason(contact: CamContact) -> str | None:
    """Why this cam contact cannot be built faithfully, if it cannot."""
    profile = contact.profile
    if isinstance(profile, EccentricDisc):
        return None
    if isinstance(profile, SplineProfile):
        return tip_reason(contact)
    if isinstance(profile, LobedProfile):
        return lobed_reason(contact) or f"cam '{contact.name}' has a lobed profile: {LOBES_ON_FACETS}"
    return f"cam '{contact.name}' has a {type(profile).__name__} profile, which MuJoCo's model does not know"


def cam_pairs(contacts: tuple[CamContact, ...], tree: Tree, pieces: int = DEFAULT_PIECES) -> list[CamPair]:
    """The contact geometry of every cam contact, placed on the tree's authored poses; a profile
    other than a disc as `pieces` facets."""
    pairs = []
    for index, contact in enumerate(contacts):
        reason = unsupported_reason(contact)
        if reason:
            raise TreeError(reason)
        profile = contact.profile
        name = f"{contact.name}_cam"
        cam: tuple[Geom, ...]
        if isinstance(profile, EccentricDisc):
            size = (profile.radius, HALF_HEIGHT * profile.radius)
            cam = (Geom(contact.cam, name, "capsule", size, (profile.eccentricity, 0.0)),)
            radius, reach = profile.radius, profile.radius + profile.eccentricity
        else:
            radius = reach = extent(profile)[1]
            thickness, segments = facets(profile, pieces, tip_radius(contact))
            cam = tuple(
                Geom(contact.cam, f"{name}{k}", "capsule", (thickness,), fromto=ends)
                for k, ends in enumerate(segments)
            )
        follower = _follower(contact, tree, radius, reach)
        joint = tree.joint_of(follower.body)
        if joint.kind == "fixed":
            raise TreeError(f"cam '{contact.name}': the follower is fixed, so it cannot be preloaded")
        by_bits = len(cam) > 1 and follower.kind == "box" and index < MASK_BITS
        pairs.append(CamPair(contact.name, cam, follower, joint.name, 1 << index if by_bits else 0))
    return pairs


def _follower(contact: CamContact, tree: Tree, radius: float, reach: float) -> Geom:
    """The follower's geom, sized by the cam's `radius` (R for a disc) and reaching past its
    largest radius `reach` (R + e) on either side."""
    name = f"{contact.name}_follower"
    reach = 2.0 * reach
    if isinstance(contact, RollerCam):
        return Geom(contact.centre.body, name, "sphere", (contact.roller_radius,), contact.centre.local)
    if isinstance(contact, FlatFaceCam):
        n = np.array(contact.normal, dtype=float)
        n /= np.linalg.norm(n)
        thickness = 0.2 * radius
        centre = np.array(contact.face.local) - n * thickness
        tangent_angle = math.atan2(n[1], n[0]) + math.pi / 2
        size = (reach, thickness, 2.0 * HALF_HEIGHT * radius)
        return Geom(contact.face.body, name, "box", size, (centre[0], centre[1]), tangent_angle)
    assert isinstance(contact, KnifeEdgeCam)
    tip_r = tip_radius(contact)
    if tip_r > 0.0:  # on facets: a sphere centred on the tip (adapters.mujoco.cam_tip)
        return Geom(contact.tip.body, name, "sphere", (tip_r,), contact.tip.local)
    # The edge points from the tip towards the cam's centre of rotation at the authored pose.
    tip = contact.tip
    toward = tree.point(Point(contact.cam)) - tree.point(tip)
    follower_angle = tree.poses[tip.body][2]
    d = rot(follower_angle).T @ toward
    d /= np.linalg.norm(d)
    half = 0.2 * radius
    centre = np.array(tip.local) - d * half * math.sqrt(2.0)
    edge_angle = math.atan2(d[1], d[0]) + math.pi / 4
    size = (half, half, 2.0 * HALF_HEIGHT * radius)
    return Geom(tip.body, name, "box", size, (centre[0], centre[1]), edge_angle)
