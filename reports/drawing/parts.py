"""The parts of a mechanism drawing every other part uses: the shape record, the locator of body
points at one instant, the points a body carries; and cams with their followers (world coordinates,
metres; reports.drawing.geometry assembles the drawing)."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from scenarios import GROUND, Scenario
from scenarios.bodies import Point, Pose, Vec2
from scenarios.cam_profiles import LobedProfile, Profile, SplineProfile
from scenarios.cams import CamContact, FlatFaceCam, KnifeEdgeCam, RollerCam, follower_body
from scenarios.drivers import (
    PointPathDriver,
    RelativeDisplacementDriver,
)
from scenarios.forces import AppliedForce, SpringDamper
from scenarios.gears import RackPinion
from scenarios.geometry import rotate, world_point
from scenarios.joints import Prismatic, Revolute, RevoluteRevolute

BLOCK_SIZE = 0.25
"""A slider's block is this many characteristic lengths long (and 0.6 of that wide)."""


@dataclass(frozen=True)
class Shape:
    """One drawn element: its `kind` says how it is drawn (reports.drawing.svg), `name` is
    the body, joint, driver or load it belongs to, `points` are world points (a circle's centre,
    a line's ends, a polygon's corners), `value` a kind's own number (an arrow's sense: +1, -1 or 0
    for both), `title` the hover text and `label` the text written beside it ('' for none)."""

    kind: str
    name: str
    points: tuple[Vec2, ...]
    radius: float = 0.0
    value: float = 0.0
    title: str = ""
    label: str = ""


class Locator:
    """World positions of body points at one instant (the ground's pose is the identity)."""

    def __init__(self, scenario: Scenario, t: float, poses: Mapping[str, Pose]) -> None:
        self.scenario = scenario
        self.t = t
        self.poses = dict(poses)
        self.size = scenario.characteristic_length

    def pose(self, body: str) -> Pose:
        return (0.0, 0.0, 0.0) if body == GROUND else self.poses[body]

    def point(self, p: Point) -> Vec2:
        return world_point(self.pose(p.body), p.local)

    def local(self, body: str, local: Vec2) -> Vec2:
        return world_point(self.pose(body), local)

    def direction(self, body: str, local: Vec2) -> Vec2:
        return rotate(self.pose(body)[2], local)


def pose_text(pose: Pose) -> str:
    return f"x = {pose[0]:.6g} m, y = {pose[1]:.6g} m, θ = {pose[2]:.6g} rad"


def point_text(p: Vec2) -> str:
    return f"x = {p[0]:.6g} m, y = {p[1]:.6g} m"


def unit(v: Vec2) -> Vec2:
    norm = math.hypot(*v)
    return (1.0, 0.0) if norm == 0.0 else (v[0] / norm, v[1] / norm)


def along(p: Vec2, u: Vec2, length: float) -> Vec2:
    return (p[0] + length * u[0], p[1] + length * u[1])


def _feature(contact: CamContact) -> Point:
    if isinstance(contact, KnifeEdgeCam):
        return contact.tip
    if isinstance(contact, RollerCam):
        return contact.centre
    return contact.face


def body_points(scenario: Scenario, body: str) -> list[Vec2]:
    """The distinct local points of `body` that joints, contacts, drivers and loads attach to."""
    points: list[Point] = []
    for j in scenario.joints:
        if isinstance(j, Revolute | Prismatic | RevoluteRevolute):
            points += [j.p_i, j.p_j]
        elif isinstance(j, RackPinion):
            points += [j.centre, j.rack]
        elif isinstance(j, KnifeEdgeCam | RollerCam | FlatFaceCam):
            points.append(_feature(j))
    for d in scenario.drivers:
        if isinstance(d, PointPathDriver):
            points.append(d.point)
        elif isinstance(d, RelativeDisplacementDriver):
            points += [d.p_i, d.p_j]
    for f in scenario.forces:
        if isinstance(f, SpringDamper):
            points += [f.p_i, f.p_j]
        elif isinstance(f, AppliedForce):
            points.append(f.point)
    found: dict[tuple[float, float], Vec2] = {}
    for p in points:
        if p.body == body:
            found.setdefault((round(p.local[0], 12), round(p.local[1], 12)), p.local)
    return list(found.values())


def _samples(profile: Profile) -> np.ndarray:
    """Profile angles fine enough for a smooth outline."""
    if isinstance(profile, LobedProfile):
        count = max(360, 48 * profile.lobes)
    elif isinstance(profile, SplineProfile):
        count = max(360, 8 * len(profile.table))
    else:
        count = 360
    return np.linspace(0.0, 2.0 * math.pi, min(count, 4800), endpoint=False)


def cam_shapes(contact: CamContact, at: Locator, phi: float | None) -> list[Shape]:
    """The cam's profile, its follower (stem with knife edge, roller or flat face) and the contact
    point at the contact parameter `phi` (none when not known)."""
    profile = contact.profile
    local = [
        (r * math.cos(a), r * math.sin(a)) for a in _samples(profile) for r in [profile.radii(float(a))[0]]
    ]
    outline = tuple(at.local(contact.cam, p) for p in local)
    reach = max(math.hypot(*p) for p in local)
    cam_pose = at.pose(contact.cam)
    centre = (cam_pose[0], cam_pose[1])
    shapes = [
        Shape(
            "cam", contact.cam, outline, title=f"cam {contact.cam}: {pose_text(cam_pose)}", label=contact.cam
        )
    ]
    follower = follower_body(contact)
    feature = at.point(_feature(contact))
    title = f"follower {follower}: {pose_text(at.pose(follower))}"
    away = unit((feature[0] - centre[0], feature[1] - centre[1]))
    guides = [
        j for j in at.scenario.joints if isinstance(j, Prismatic) and follower in (j.p_i.body, j.p_j.body)
    ]
    for j in guides:  # a translating follower's stem lies along its guide
        u = unit(at.direction(j.p_i.body, j.axis))
        sense = 1.0 if u[0] * away[0] + u[1] * away[1] >= 0 else -1.0
        away = (sense * u[0], sense * u[1])
    if isinstance(contact, FlatFaceCam):
        n = unit(at.direction(follower, contact.normal))
        tangent = (-n[1], n[0])
        foot = (centre[0] - feature[0]) * tangent[0] + (centre[1] - feature[1]) * tangent[1]
        middle = along(feature, tangent, foot)
        ends = (along(middle, tangent, -1.1 * reach), along(middle, tangent, 1.1 * reach))
        shapes.append(Shape("face", follower, ends, title=title))
        away = (-n[0], -n[1])
        start = feature
    elif isinstance(contact, RollerCam):
        shapes.append(Shape("roller", follower, (feature,), radius=contact.roller_radius, title=title))
        start = feature
    else:
        w = 0.12 * reach
        side = (-away[1], away[0])
        base = along(feature, away, 2.0 * w)
        knife = (feature, along(base, side, w), along(base, side, -w))
        shapes.append(Shape("knife", follower, knife, title=title))
        start = base
    shapes.append(Shape("stem", follower, (start, along(start, away, reach)), title=title, label=follower))
    for j in guides:  # its guide: a sleeve about the stem's far half
        sleeve = (along(start, away, 0.55 * reach), along(start, away, 0.95 * reach))
        text = f"prismatic {j.name}: the follower's guide, along ({away[0]:.4g}, {away[1]:.4g})"
        kind = "sleeve" if GROUND in (j.p_i.body, j.p_j.body) else "guide"
        shapes.append(Shape(kind, j.name, sleeve, title=text, label=j.name))
    if phi is not None and math.isfinite(phi):
        d = profile.radii(phi)[0]
        touch = at.local(contact.cam, (d * math.cos(phi), d * math.sin(phi)))
        text = f"cam contact {contact.name}: φ = {phi:.6g} rad, {point_text(touch)}"
        shapes.append(Shape("contact", contact.name, (touch,), title=text, label=contact.name))
    return shapes
