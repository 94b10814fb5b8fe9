"""Drivers, springs and applied loads in a mechanism drawing: an arc on a driven angle, an arrow on a
driven position, a zigzag for a spring-damper (world coordinates; reports.drawing.geometry
assembles them)."""

from __future__ import annotations

import math

from reports.drawing.parts import BLOCK_SIZE, Locator, Shape, along, point_text, unit
from scenarios import GROUND, Scenario
from scenarios.bodies import Vec2
from scenarios.drivers import AbsoluteDriver, Driver, PointPathDriver, RelativeRotationDriver
from scenarios.forces import AppliedForce, AppliedTorque, SpringDamper
from scenarios.joints import Revolute
from scenarios.motions import ConstantSpeed, Harmonic, Motion


def _sense(motion: Motion, t: float) -> float:
    """+1 or -1 for a motion that keeps one sense, 0 (both) for one that goes back and forth."""
    if isinstance(motion, ConstantSpeed):
        return math.copysign(1.0, motion.rate) if motion.rate else 0.0
    if isinstance(motion, Harmonic):
        return 0.0
    rate = motion.df(t)
    return 0.0 if rate == 0.0 else math.copysign(1.0, rate)


def _pivot(at: Locator, body_i: str, body_j: str) -> Vec2:
    """Where bodies i and j are pinned together; body i's frame origin when they are not."""
    for j in at.scenario.joints:
        if isinstance(j, Revolute) and {j.p_i.body, j.p_j.body} == {body_i, body_j}:
            return at.point(j.p_i)
    pose = at.pose(body_i)
    return (pose[0], pose[1])


def driver_shapes(scenario: Scenario, at: Locator) -> list[Shape]:
    """An arc on a driven angle, an arrow on a driven position, a ring on a driven point."""
    return [_driver_shape(d, at) for d in scenario.drivers]


def _driver_shape(d: Driver, at: Locator) -> Shape:
    if isinstance(d, AbsoluteDriver):
        return _absolute(d, at)
    if isinstance(d, RelativeRotationDriver):
        title = f"driver {d.name}: θ({d.body_i}) - θ({d.body_j}) = {d.motion.f(at.t):.6g} rad"
        centre = _pivot(at, d.body_i, d.body_j)
        return Shape("driver_arc", d.name, (centre,), value=_sense(d.motion, at.t), title=title, label=d.name)
    if isinstance(d, PointPathDriver):
        p = at.point(d.point)
        title = f"driver {d.name}: path point at {point_text(p)}"
        return Shape("driver_point", d.name, (p,), title=title, label=d.name)
    ends = (at.point(d.p_j), at.point(d.p_i))
    title = f"driver {d.name}: relative displacement"
    return Shape("driver_line", d.name, ends, value=0.0, title=title, label=d.name)


def _absolute(d: AbsoluteDriver, at: Locator) -> Shape:
    """An arc about the body's pivot for a driven angle; an arrow along x or y for a position."""
    value = d.motion.f(at.t)
    title = f"driver {d.name}: {d.body}.{d.coordinate} = {value:.6g} at t = {at.t:.6g} s"
    if d.coordinate == "theta":
        centre = _pivot(at, d.body, GROUND)
        return Shape("driver_arc", d.name, (centre,), value=_sense(d.motion, at.t), title=title, label=d.name)
    pose = at.pose(d.body)
    u = (1.0, 0.0) if d.coordinate == "x" else (0.0, 1.0)
    origin = (pose[0], pose[1])  # the arrow starts clear of a slider's block
    ends = (along(origin, u, BLOCK_SIZE * at.size), along(origin, u, (BLOCK_SIZE + 0.5) * at.size))
    return Shape("driver_line", d.name, ends, value=_sense(d.motion, at.t), title=title, label=d.name)


def spring_shapes(scenario: Scenario, at: Locator) -> list[Shape]:
    """Spring-dampers as zigzags between their points, applied forces as arrows, torques as arcs."""
    shapes: list[Shape] = []
    for f in scenario.forces:
        if isinstance(f, SpringDamper):
            ends = (at.point(f.p_i), at.point(f.p_j))
            length = math.dist(*ends)
            title = f"spring-damper {f.name}: length {length:.6g} m, k = {f.stiffness:.6g} N/m"
            shapes.append(Shape("spring", f.name, ends, title=title, label=f.name))
            for p in (f.p_i, f.p_j):
                if p.body == GROUND:
                    shapes.append(
                        Shape("anchor", f.name, (at.point(p),), title=f"{f.name} anchored to the ground")
                    )
        elif isinstance(f, AppliedForce):
            where = at.point(f.point)
            force = (f.fx.f(at.t), f.fy.f(at.t))
            if math.hypot(*force) > 0:
                title = f"force {f.name}: ({force[0]:.6g}, {force[1]:.6g}) N at {point_text(where)}"
                tip = along(where, unit(force), 0.4 * at.size)
                shapes.append(Shape("force", f.name, (where, tip), value=1.0, title=title, label=f.name))
        elif isinstance(f, AppliedTorque):
            centre = _pivot(at, f.body, f.reaction)
            torque = f.torque.f(at.t)
            title = f"torque {f.name} on {f.body}: {torque:.6g} N m"
            sense = 0.0 if torque == 0 else math.copysign(1.0, torque)
            shapes.append(Shape("torque", f.name, (centre,), value=sense, title=title, label=f.name))
    return shapes
