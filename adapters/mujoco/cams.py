"""Cam contacts as MuJoCo contact geometry (no MuJoCo here).

MuJoCo has no cam joint: the cam is real geometry and the follower is held on it by a preloaded
spring, through a frictionless contact pair. The eccentric disc is a capsule whose axis is normal to
the plane (its section in the plane is exactly the disc, and MuJoCo's capsule colliders are
analytic); the roller is a sphere, the flat face the face of a box, the knife edge the edge of a box
turned 45 degrees about its point. A spline or lobed profile would have to be a mesh, which MuJoCo
collides as its convex hull with a general convex solver: not a faithful cam, so it is refused.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from adapters.mujoco.tree import Tree, TreeError, rot
from scenarios.bodies import Point
from scenarios.cam_profiles import EccentricDisc, LobedProfile, SplineProfile
from scenarios.cams import CamContact, FlatFaceCam, KnifeEdgeCam, RollerCam

HALF_HEIGHT = 0.2
"""Half-thickness of all cam geometry normal to the plane, in cam disc radii."""


@dataclass(frozen=True)
class Geom:
    """One geom: the body it sits on and its MJCF attributes (name, type, size, pos, quat)."""

    body: str
    name: str
    kind: str
    size: tuple[float, ...]
    pos: tuple[float, float] = (0.0, 0.0)
    angle: float = 0.0


@dataclass(frozen=True)
class CamPair:
    """The two geoms of one cam contact and the follower joint that carries the preload spring."""

    name: str
    cam: Geom
    follower: Geom
    spring_joint: str


def unsupported_reason(contact: CamContact) -> str | None:
    """Why this cam contact cannot be built faithfully, if it cannot."""
    profile = contact.profile
    if isinstance(profile, EccentricDisc):
        return None
    mesh = (
        "MuJoCo has no analytic collider for it and could only mesh it, and a mesh collides as the "
        "convex hull of its vertices, a polygon of flat facets"
    )
    if isinstance(profile, SplineProfile):
        return (
            f"cam '{contact.name}' has a spline profile: {mesh}: the follower's velocity would be "
            "piecewise constant and its acceleration impulsive, not the smooth spline's"
        )
    if isinstance(profile, LobedProfile):
        concave = profile.valley_curvature_radius() < 0.0
        hull = (
            "; the hull would also fill its concave valleys, which the follower could never enter"
            if concave
            else ": the follower's velocity would be piecewise constant, not the smooth lobes'"
        )
        return f"cam '{contact.name}' has a lobed profile ({profile.lobes} lobes): {mesh}{hull}"
    return f"cam '{contact.name}' has a {type(profile).__name__} profile: {mesh}"


def cam_pairs(contacts: tuple[CamContact, ...], tree: Tree) -> list[CamPair]:
    """The contact geometry of every cam contact, placed on the tree's authored poses."""
    pairs = []
    for contact in contacts:
        reason = unsupported_reason(contact)
        if reason:
            raise TreeError(reason)
        disc = contact.profile
        assert isinstance(disc, EccentricDisc)
        cam = Geom(
            contact.cam,
            f"{contact.name}_cam",
            "capsule",
            (disc.radius, HALF_HEIGHT * disc.radius),
            (disc.eccentricity, 0.0),
        )
        follower = _follower(contact, tree, disc)
        joint = tree.joint_of(follower.body)
        if joint.kind == "fixed":
            raise TreeError(f"cam '{contact.name}': the follower is fixed, so it cannot be preloaded")
        pairs.append(CamPair(contact.name, cam, follower, joint.name))
    return pairs


def _follower(contact: CamContact, tree: Tree, disc: EccentricDisc) -> Geom:
    name = f"{contact.name}_follower"
    reach = 2.0 * (disc.radius + disc.eccentricity)
    if isinstance(contact, RollerCam):
        return Geom(contact.centre.body, name, "sphere", (contact.roller_radius,), contact.centre.local)
    if isinstance(contact, FlatFaceCam):
        n = np.array(contact.normal, dtype=float)
        n /= np.linalg.norm(n)
        thickness = 0.2 * disc.radius
        centre = np.array(contact.face.local) - n * thickness
        tangent_angle = math.atan2(n[1], n[0]) + math.pi / 2
        size = (reach, thickness, 2.0 * HALF_HEIGHT * disc.radius)
        return Geom(contact.face.body, name, "box", size, (centre[0], centre[1]), tangent_angle)
    assert isinstance(contact, KnifeEdgeCam)
    # The edge points from the tip towards the cam's centre of rotation at the authored pose.
    tip = contact.tip
    toward = tree.point(Point(contact.cam)) - tree.point(tip)
    follower_angle = tree.poses[tip.body][2]
    d = rot(follower_angle).T @ toward
    d /= np.linalg.norm(d)
    half = 0.2 * disc.radius
    centre = np.array(tip.local) - d * half * math.sqrt(2.0)
    edge_angle = math.atan2(d[1], d[0]) + math.pi / 4
    size = (half, half, 2.0 * HALF_HEIGHT * disc.radius)
    return Geom(tip.body, name, "box", size, (centre[0], centre[1]), edge_angle)
