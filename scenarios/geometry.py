"""Planar frames: a unit direction, rotating a vector, composing poses, and a body point in world
coordinates.

Values only; constraint code that needs derivatives writes its own inside each engine, so that the
engines check each other independently.
"""

from __future__ import annotations

import math

from scenarios.bodies import Pose, Vec2


def unit(v: Vec2) -> Vec2:
    """v / |v|: a declared axis as a direction (scenarios accept any non-zero length)."""
    norm = math.hypot(v[0], v[1])
    return (v[0] / norm, v[1] / norm)


def rotate(angle: float, v: Vec2) -> Vec2:
    """A(angle) v."""
    c, s = math.cos(angle), math.sin(angle)
    return (c * v[0] - s * v[1], s * v[0] + c * v[1])


def compose(a: Pose, b: Pose) -> Pose:
    """Pose b, given in frame a, expressed in a's parent frame."""
    x, y = rotate(a[2], (b[0], b[1]))
    return (a[0] + x, a[1] + y, a[2] + b[2])


def world_point(pose: Pose, local: Vec2) -> Vec2:
    """The world position of the point at `local` on a body whose frame is at `pose`."""
    x, y = rotate(pose[2], local)
    return (pose[0] + x, pose[1] + y)
