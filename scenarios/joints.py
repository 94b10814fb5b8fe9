"""Kinematic joints: time-independent constraints between two bodies (or a body and the ground)."""

from __future__ import annotations

from dataclasses import dataclass

from scenarios.bodies import Point, Pose, Vec2


@dataclass(frozen=True)
class Ground:
    """Fixes all three coordinates of `body` at `pose`. Three rows."""

    name: str
    body: str
    pose: Pose


@dataclass(frozen=True)
class Revolute:
    """Pin joint: point `p_i` coincides with point `p_j`. Two rows."""

    name: str
    p_i: Point
    p_j: Point


@dataclass(frozen=True)
class Prismatic:
    """Translational joint between p_i.body and p_j.body. Two rows.

    `axis` is the sliding direction in body i's frame; the points p_i and p_j lie on the axis.
    `angle` is the constant theta_i - theta_j.
    """

    name: str
    p_i: Point
    p_j: Point
    axis: Vec2 = (1.0, 0.0)
    angle: float = 0.0


@dataclass(frozen=True)
class RevoluteRevolute:
    """A massless link of `length` between points p_i and p_j. One row."""

    name: str
    p_i: Point
    p_j: Point
    length: float


Joint = Ground | Revolute | Prismatic | RevoluteRevolute
