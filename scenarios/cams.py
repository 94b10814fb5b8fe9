"""Cam contacts. Each adds one unknown, the profile parameter phi of the contact point, and two rows."""

from __future__ import annotations

from dataclasses import dataclass

from scenarios.bodies import Point, Vec2
from scenarios.cam_profiles import Profile


@dataclass(frozen=True)
class KnifeEdgeCam:
    """The follower's tip `tip` touches the cam profile: r_cam(phi) - r_tip = 0."""

    name: str
    cam: str
    profile: Profile
    tip: Point
    phi_guess: float


@dataclass(frozen=True)
class RollerCam:
    """A roller of `roller_radius` centred at `centre` (on the follower) rolls on the profile:
    n.t = 0 and n.n - r^2 = 0 with n = r_centre - r_cam(phi) and t the profile tangent."""

    name: str
    cam: str
    profile: Profile
    centre: Point
    roller_radius: float
    phi_guess: float


@dataclass(frozen=True)
class FlatFaceCam:
    """A flat face through `face` with unit normal `normal` (in the follower's frame) touches the
    profile: h.t = 0 and h.(r_cam(phi) - r_face) = 0."""

    name: str
    cam: str
    profile: Profile
    face: Point
    normal: Vec2
    phi_guess: float


CamContact = KnifeEdgeCam | RollerCam | FlatFaceCam


def follower_body(contact: CamContact) -> str:
    """The body that carries a cam's follower: the knife edge's tip, the roller's centre or the
    flat face's body."""
    if isinstance(contact, KnifeEdgeCam):
        return contact.tip.body
    if isinstance(contact, RollerCam):
        return contact.centre.body
    return contact.face.body
