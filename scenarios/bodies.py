"""Rigid bodies of a planar mechanism and the points fixed on them."""

from __future__ import annotations

from dataclasses import dataclass

GROUND = "ground"
"""Name of the fixed frame. It is not a body of the scenario: its frame is the global frame."""

Vec2 = tuple[float, float]
Pose = tuple[float, float, float]


@dataclass(frozen=True)
class Body:
    """A moving rigid body with absolute coordinates (x, y, theta) of its body frame.

    `guess` is a rough initial pose: the solver assembles the mechanism from it, so it only has to
    be near the intended assembly branch. Mass and inertia (about the frame origin, which is also
    the centre of mass) matter only to the dynamic engines; a kinematically driven result must not
    depend on them.
    """

    name: str
    guess: Pose
    mass: float = 1.0
    inertia: float = 1.0e-3
    length: float = 0.0
    """Distance between the body's two joints for a link (0 for gears, cams, sliders): used for
    drawing and default inertia only."""
    rate: Pose = (0.0, 0.0, 0.0)
    """Initial (vx, vy, omega) for forward dynamics; the solver projects it onto the velocity
    constraints (the nearest consistent rates in the kinetic-energy norm)."""


@dataclass(frozen=True)
class Point:
    """A point fixed on `body` at local coordinates `local` in that body's frame.

    On the ground, `local` is the global position.
    """

    body: str
    local: Vec2 = (0.0, 0.0)
