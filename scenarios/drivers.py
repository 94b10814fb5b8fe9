"""Drivers: time-dependent constraints that prescribe the motion of the mechanism's inputs."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from scenarios.bodies import Point
from scenarios.motions import Motion

Coordinate = Literal["x", "y", "theta"]


@dataclass(frozen=True)
class AbsoluteDriver:
    """One absolute coordinate of `body` follows `motion`: q - f(t) = 0. One row."""

    name: str
    body: str
    coordinate: Coordinate
    motion: Motion


@dataclass(frozen=True)
class RelativeRotationDriver:
    """theta_i - theta_j - f(t) = 0. One row."""

    name: str
    body_i: str
    body_j: str
    motion: Motion


@dataclass(frozen=True)
class PointPathDriver:
    """A point on a body follows a path in the plane: r^P - (fx(t), fy(t)) = 0. Two rows."""

    name: str
    point: Point
    motion_x: Motion
    motion_y: Motion


@dataclass(frozen=True)
class RelativeDisplacementDriver:
    """r^P_i - r^P_j - (fx(t), fy(t)) = 0, in global axes. Two rows."""

    name: str
    p_i: Point
    p_j: Point
    motion_x: Motion
    motion_y: Motion


Driver = AbsoluteDriver | RelativeRotationDriver | PointPathDriver | RelativeDisplacementDriver
