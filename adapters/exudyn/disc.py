"""Followers on a circular disc cam as Exudyn's own joints: a knife edge or roller keeps a fixed
distance from the disc's centre (a distance connector); a flat face keeps the disc's centre at the
normal distance R from its plane (a 2D prismatic joint without its rotation constraint, sliding the
centre along the face line moved R towards the disc). No Exudyn import here: only the geometry, and
the contact parameter phi recovered from the bodies' poses afterwards.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from scenarios.bodies import GROUND, Point
from scenarios.cam_profiles import EccentricDisc
from scenarios.cams import FlatFaceCam, KnifeEdgeCam, RollerCam
from scenarios.geometry import world_point
from scenarios.scenario import Scenario

PhiFromPoses = Callable[[np.ndarray, np.ndarray], float]


@dataclass(frozen=True)
class DiscContact:
    """`follower` stays `reach` from `centre`; `phi(cam_pose, follower_pose)` is the contact's
    profile parameter, the polar angle of the contact point in the cam frame."""

    centre: Point
    follower: Point
    reach: float
    phi: PhiFromPoses


def disc_contact(scenario: Scenario, cam: KnifeEdgeCam | RollerCam, disc: EccentricDisc) -> DiscContact:
    """The distance form of `cam`; a roller takes the outer or inner contact, whichever the
    bodies' guessed poses are nearer."""
    centre = Point(cam.cam, (disc.eccentricity, 0.0))
    follower = cam.tip if isinstance(cam, KnifeEdgeCam) else cam.centre
    reach, side = disc.radius, 1.0
    if isinstance(cam, RollerCam):
        gap = float(np.linalg.norm(_guessed(scenario, follower) - _guessed(scenario, centre)))
        outer, inner = disc.radius + cam.roller_radius, abs(disc.radius - cam.roller_radius)
        if abs(gap - inner) < abs(gap - outer):
            # a disc inside a ring roller touches it on the far side of its centre
            reach, side = inner, (-1.0 if cam.roller_radius > disc.radius else 1.0)
        else:
            reach = outer
    return DiscContact(centre, follower, reach, _contact_phi(disc, follower.local, side))


@dataclass(frozen=True)
class FlatFaceDisc:
    """The disc's `centre` slides on the line through `slider` (a point of the follower) with unit
    `normal` (the follower's frame); `phi(cam_pose, follower_pose)` as for DiscContact."""

    centre: Point
    slider: Point
    normal: tuple[float, float]
    phi: PhiFromPoses


def flat_face_disc(scenario: Scenario, cam: FlatFaceCam, disc: EccentricDisc) -> FlatFaceDisc:
    """h.(C - face) = +-R as a point on a line: the sign is the side of the face the disc is on at
    the guessed poses."""
    centre = Point(cam.cam, (disc.eccentricity, 0.0))
    h = np.asarray(cam.normal, dtype=float) / float(np.hypot(*cam.normal))
    theta = scenario.body(cam.face.body).guess[2] if cam.face.body != GROUND else 0.0
    c, s = math.cos(theta), math.sin(theta)
    h_world = np.array([c * h[0] - s * h[1], s * h[0] + c * h[1]])
    side = (
        1.0 if float(h_world @ (_guessed(scenario, centre) - _guessed(scenario, cam.face))) >= 0.0 else -1.0
    )
    offset = side * disc.radius
    slider = Point(cam.face.body, (cam.face.local[0] + offset * h[0], cam.face.local[1] + offset * h[1]))
    eccentric = np.array([disc.eccentricity, 0.0])

    def phi(cam_pose: np.ndarray, follower: np.ndarray) -> float:
        """The polar angle, in the cam frame, of the disc point nearest the face: C - side R h."""
        cf, sf = math.cos(follower[2]), math.sin(follower[2])
        normal = np.array([cf * h[0] - sf * h[1], sf * h[0] + cf * h[1]])
        cc, sc = math.cos(cam_pose[2]), math.sin(cam_pose[2])
        in_cam = eccentric - offset * np.array(
            [cc * normal[0] + sc * normal[1], -sc * normal[0] + cc * normal[1]]
        )
        return math.atan2(in_cam[1], in_cam[0])

    return FlatFaceDisc(centre, slider, (float(h[0]), float(h[1])), phi)


def _guessed(scenario: Scenario, point: Point) -> np.ndarray:
    """A point's global position at the bodies' guessed poses."""
    if point.body == GROUND:
        return np.array(point.local, dtype=float)
    return np.array(world_point(scenario.body(point.body).guess, point.local))


def _contact_phi(disc: EccentricDisc, local: tuple[float, float], side: float) -> PhiFromPoses:
    """The polar angle, in the cam frame, of the disc's circle point on the line from its centre
    to the follower's point (on the far side for a disc inside a ring roller)."""
    centre = np.array([disc.eccentricity, 0.0])

    def phi(cam: np.ndarray, follower: np.ndarray) -> float:
        point = np.array(world_point((follower[0], follower[1], follower[2]), local))
        c, s = math.cos(cam[2]), math.sin(cam[2])
        rel = point - cam[:2]
        in_cam = np.array([c * rel[0] + s * rel[1], -s * rel[0] + c * rel[1]])
        direction = (in_cam - centre) / float(np.linalg.norm(in_cam - centre))
        contact = centre + side * disc.radius * direction
        return math.atan2(contact[1], contact[0])

    return phi
