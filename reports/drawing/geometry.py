"""What a drawing of a planar mechanism shows at one instant, in world coordinates (metres).

From a scenario and the poses of its bodies at one time, the shapes of a drawing: every body (a
link as a bar or plate through its joint points, a slider as a block, a gear as its pitch circle, a
cam as its profile, a follower as its stem with its knife edge, roller or flat face), every joint
(a revolute as a pin, a prismatic as its guide line, ground pivots hatched), the drivers (an arc or
an arrow on the driven coordinate) and the springs. Geometry only: how shapes look on a page is
reports.drawing.svg's. The scenario is read, never changed.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass

import numpy as np

from reports.drawing.drivers import driver_shapes, spring_shapes
from reports.drawing.parts import (
    BLOCK_SIZE,
    Locator,
    Shape,
    body_points,
    cam_shapes,
    point_text,
    pose_text,
)
from scenarios import GROUND, Scenario
from scenarios.bodies import Pose, Vec2
from scenarios.cams import follower_body
from scenarios.geometry import rotate
from scenarios.joints import Ground, Prismatic, Revolute, RevoluteRevolute

__all__ = ["Instant", "Shape", "instant"]


@dataclass(frozen=True)
class Instant:
    """The shapes of the mechanism at time `t`, each in world coordinates."""

    t: float
    shapes: tuple[Shape, ...]


def instant(scenario: Scenario, t: float, poses: Mapping[str, Pose], extras: Mapping[str, float]) -> Instant:
    """The drawing's shapes at time `t`, given every body's pose and the contacts' parameters
    (`<contact>.phi`, as the native solver's trajectory names them)."""
    at = Locator(scenario, t, poses)
    shapes: list[Shape] = []
    shapes += _body_shapes(scenario, at)
    for contact in scenario.cams:
        shapes += cam_shapes(contact, at, extras.get(f"{contact.name}.phi"))
    shapes += _gear_shapes(scenario, at)
    shapes += _joint_shapes(scenario, at)
    shapes += spring_shapes(scenario, at)
    shapes += driver_shapes(scenario, at)
    return Instant(t, tuple(shapes))


def _hull(points: Iterable[Vec2]) -> list[Vec2]:
    """The convex hull, counter-clockwise (Andrew's monotone chain); fewer points when collinear."""
    pts = sorted(set(points))
    if len(pts) <= 2:
        return pts

    def cross(o: Vec2, a: Vec2, b: Vec2) -> float:
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower: list[Vec2] = []
    upper: list[Vec2] = []
    for p in pts:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    for p in reversed(pts):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return lower[:-1] + upper[:-1]


def _special_bodies(scenario: Scenario) -> set[str]:
    """Bodies drawn by their own shape (gears, cams, racks, followers), not as links."""
    from scenarios.gears import GearPair, RackPinion

    names: set[str] = set()
    for j in scenario.joints:
        if isinstance(j, GearPair):
            names |= {j.gear_i, j.gear_j}
        elif isinstance(j, RackPinion):
            names |= {j.centre.body, j.rack.body}
    for c in scenario.cams:
        names.add(c.cam)
    return names - {GROUND}


def _sliding(scenario: Scenario) -> dict[str, Prismatic]:
    """Each body that slides in a prismatic joint (not the one that carries the guide), with that
    joint: the moving one against the ground; between moving bodies the one without a length
    (a block in a slotted link), else body i (whose frame holds the axis)."""
    found: dict[str, Prismatic] = {}
    for j in scenario.joints:
        if isinstance(j, Prismatic):
            i, k = j.p_i.body, j.p_j.body
            if GROUND in (i, k):
                slider = k if i == GROUND else i
            elif scenario.body(k).length == 0.0 and scenario.body(i).length > 0.0:
                slider = k
            else:
                slider = i
            found.setdefault(slider, j)
    return found


def _body_shapes(scenario: Scenario, at: Locator) -> list[Shape]:
    """Links as bars or plates through their points, sliders as blocks, other bodies as discs."""
    shapes: list[Shape] = []
    special, sliding = _special_bodies(scenario), _sliding(scenario)
    followers = {follower_body(c) for c in scenario.cams}
    for body in scenario.bodies:
        pose = at.pose(body.name)
        title = f"body {body.name}: {pose_text(pose)}"
        if body.name in special:
            continue
        local = body_points(scenario, body.name)
        if len(local) == 1 and body.length > 0:  # one pin: the link hangs from it along its axis
            p = local[0]
            norm = math.hypot(*p)
            d = (-p[0] / norm, -p[1] / norm) if norm > 0 else (1.0, 0.0)
            local.append((p[0] + body.length * d[0], p[1] + body.length * d[1]))
        outline = _hull(at.local(body.name, p) for p in local)
        if body.name in sliding and body.name not in followers:
            shapes.append(_block(body.name, pose, sliding[body.name], at, title))
            if len(outline) >= 2 and _span(outline) > BLOCK_SIZE * at.size:
                shapes.append(
                    Shape("bar" if len(outline) == 2 else "plate", body.name, tuple(outline), title=title)
                )
        elif len(outline) >= 2:
            kind = "bar" if len(outline) == 2 else "plate"
            shapes.append(Shape(kind, body.name, tuple(outline), title=title, label=body.name))
        elif body.name not in followers:
            centre = (pose[0], pose[1])
            radius = 0.25 * BLOCK_SIZE * at.size
            shapes.append(Shape("disc", body.name, (centre,), radius=radius, title=title, label=body.name))
            shapes.append(
                Shape("spoke", body.name, (centre, at.local(body.name, (radius, 0.0))), title=title)
            )
    return shapes


def _span(points: list[Vec2]) -> float:
    a = np.asarray(points)
    return float(np.max(np.ptp(a, axis=0)))


def _block(name: str, pose: Pose, joint: Prismatic, at: Locator, title: str) -> Shape:
    """A slider's block: a rectangle at its frame origin, long along the sliding axis."""
    axis = at.direction(joint.p_i.body, joint.axis)
    angle = math.atan2(axis[1], axis[0])
    half_long, half_short = 0.5 * BLOCK_SIZE * at.size, 0.3 * BLOCK_SIZE * at.size
    corners = tuple(
        (pose[0] + dx, pose[1] + dy)
        for dx, dy in (
            rotate(angle, (sx * half_long, sy * half_short))
            for sx, sy in ((-1, -1), (1, -1), (1, 1), (-1, 1))
        )
    )
    return Shape("block", name, corners, title=title, label=name)


def _gear_shapes(scenario: Scenario, at: Locator) -> list[Shape]:
    """Pitch circles (a ring's drawn as a ring), each with a spoke that shows its turning; a rack
    as its pitch line with teeth marks."""
    from scenarios.gears import GearPair, RackPinion

    shapes: list[Shape] = []
    for j in scenario.joints:
        if isinstance(j, GearPair):
            for gear, radius, ring in ((j.gear_i, j.radius_i, False), (j.gear_j, j.radius_j, j.internal)):
                centre = _gear_centre(scenario, at, gear, j.carrier)
                kind = "ring" if ring else "gear"
                shapes += _gear(gear, centre, radius, at.pose(gear)[2], kind, j.name)
            c_i, c_j = (_gear_centre(scenario, at, g, j.carrier) for g in (j.gear_i, j.gear_j))
            toward = (
                (c_j[0] - c_i[0], c_j[1] - c_i[1]) if not j.internal else (c_i[0] - c_j[0], c_i[1] - c_j[1])
            )
            norm = math.hypot(*toward) or 1.0
            pitch = (c_i[0] + j.radius_i * toward[0] / norm, c_i[1] + j.radius_i * toward[1] / norm)
            title = f"gear mesh {j.name}: {j.gear_i} on {j.gear_j}, pitch point {point_text(pitch)}"
            shapes.append(Shape("mesh", j.name, (pitch,), title=title, label=j.name))
        elif isinstance(j, RackPinion):
            pose = at.pose(j.centre.body)
            shapes += _gear(j.centre.body, at.point(j.centre), j.radius, pose[2], "gear", j.name)
            u = at.direction(j.rack.body, j.axis)
            p = at.point(j.rack)
            half = 3.0 * max(j.radius, at.size)
            ends = ((p[0] - half * u[0], p[1] - half * u[1]), (p[0] + half * u[0], p[1] + half * u[1]))
            c = at.point(j.centre)
            pitch = (c[0] + j.radius * u[1], c[1] - j.radius * u[0])  # the pinion lies left of u
            text = f"rack and pinion {j.name}: pitch point {point_text(pitch)}"
            shapes.append(Shape("mesh", j.name, (pitch,), title=text, label=j.name))
            rack_pose = at.pose(j.rack.body)
            title = f"rack {j.rack.body}: {pose_text(rack_pose)}"
            shapes.append(Shape("rack", j.rack.body, ends, title=title, label=j.rack.body))
    return shapes


def _gear_centre(scenario: Scenario, at: Locator, gear: str, carrier: str) -> Vec2:
    """A moving gear's centre is its frame origin; the ground's (a fixed sun) is where its carrier
    is pinned to the ground."""
    if gear != GROUND:
        pose = at.pose(gear)
        return (pose[0], pose[1])
    for j in scenario.joints:
        if isinstance(j, Revolute) and {j.p_i.body, j.p_j.body} == {carrier, GROUND}:
            return at.point(j.p_i if j.p_i.body == GROUND else j.p_j)
    return (0.0, 0.0)


def _gear(name: str, centre: Vec2, radius: float, angle: float, kind: str, mesh: str) -> list[Shape]:
    label = f"{name} (fixed gear)" if name == GROUND else name
    title = (
        f"gear {label} ({mesh}): pitch radius {radius:.6g} m, centre {point_text(centre)}, "
        f"θ = {angle:.6g} rad"
    )
    tip = (centre[0] + radius * math.cos(angle), centre[1] + radius * math.sin(angle))
    return [
        Shape(kind, name, (centre,), radius=radius, title=title, label=label),
        Shape("spoke", name, (centre, tip), title=title),
    ]


def _joint_shapes(scenario: Scenario, at: Locator) -> list[Shape]:
    """Revolute pins (ground pivots with their support), prismatic guides, massless links."""
    shapes: list[Shape] = []
    followers = {follower_body(c) for c in scenario.cams}
    for j in scenario.joints:
        if isinstance(j, Revolute):
            centre = at.point(j.p_i)
            grounded = GROUND in (j.p_i.body, j.p_j.body)
            title = f"revolute {j.name}: {point_text(centre)}"
            if grounded:
                shapes.append(Shape("ground_pivot", j.name, (centre,), title=f"ground pivot of {j.name}"))
            shapes.append(Shape("revolute", j.name, (centre,), title=title, label=j.name))
        elif isinstance(j, Prismatic) and not followers & {j.p_i.body, j.p_j.body}:
            shapes.append(_guide(j, at))
        elif isinstance(j, RevoluteRevolute):
            ends = (at.point(j.p_i), at.point(j.p_j))
            title = f"massless link {j.name}: length {j.length:.6g} m"
            shapes.append(Shape("bar", j.name, ends, title=title, label=j.name))
            shapes += [Shape("revolute", j.name, (e,), title=f"{j.name} end: {point_text(e)}") for e in ends]
        elif isinstance(j, Ground):
            centre = (j.pose[0], j.pose[1])
            shapes.append(
                Shape("ground_pivot", j.name, (centre,), title=f"{j.body} fixed by {j.name}", label=j.name)
            )
    return shapes


def _guide(j: Prismatic, at: Locator) -> Shape:
    """A prismatic joint's guide: on the ground a line across the view, hatched; between moving
    bodies a segment through the sliding point."""
    u = at.direction(j.p_i.body, j.axis)
    norm = math.hypot(*u)
    u = (u[0] / norm, u[1] / norm)
    grounded = GROUND in (j.p_i.body, j.p_j.body)
    base = at.point(j.p_i if j.p_i.body == GROUND or not grounded else j.p_j)
    title = f"prismatic {j.name}: guide through {point_text(base)} along ({u[0]:.4g}, {u[1]:.4g})"
    at_slider = at.point(j.p_j if j.p_i.body == GROUND else j.p_i)
    if grounded:  # the line through base along u, labelled where the slider is
        line = (base, (base[0] + u[0], base[1] + u[1]), at_slider)
        return Shape("ground_guide", j.name, line, title=title, label=j.name)
    half = 1.5 * BLOCK_SIZE * at.size
    ends = (
        (at_slider[0] - half * u[0], at_slider[1] - half * u[1]),
        (at_slider[0] + half * u[0], at_slider[1] + half * u[1]),
    )
    return Shape("guide", j.name, ends, title=title, label=j.name)
