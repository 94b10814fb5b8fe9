"""Gear constraints: spur gear pairs on a carrier and rack and pinion."""

from __future__ import annotations

from dataclasses import dataclass

from scenarios.bodies import GROUND, Point, Vec2


@dataclass(frozen=True)
class GearPair:
    """Spur gears i and j with pitch radii, both pinned to `carrier` (the ground for fixed centres).

    External mesh:  r_i (th_i - th_i0) + r_j (th_j - th_j0) - (r_i + r_j)(th_k - th_k0) = 0.
    Internal mesh (j is the ring): the sign of the r_j terms flips. One row, linear.
    Either gear may be the ground (a fixed sun). The reference angles are those of one assembled
    configuration.
    """

    name: str
    gear_i: str
    radius_i: float
    gear_j: str
    radius_j: float
    carrier: str = GROUND
    internal: bool = False
    theta0_i: float = 0.0
    theta0_j: float = 0.0
    theta0_carrier: float = 0.0


@dataclass(frozen=True)
class RackPinion:
    """Pinion rolling on a rack without slip. One row.

    With u the rack's unit axis (`axis` in the rack's frame), c the pinion's centre and P a point on
    the rack's pitch line: u.(r_P - r_c) - radius (th_pinion - th_rack) - offset = 0. The pinion lies
    on the left of the axis (u turned by +90 deg points from the pitch line to the pinion), so a
    positive pinion rotation moves the rack along +u.
    """

    name: str
    centre: Point
    """The pinion's centre, on the pinion."""
    radius: float
    rack: Point
    """A point of the pitch line, on the rack."""
    axis: Vec2 = (1.0, 0.0)
    offset: float = 0.0
