"""Mechanisms outside the catalogue that several engines' tests build."""

from __future__ import annotations

from scenarios import GROUND, Body, GearPair, Point, Revolute


def differential_train(rs: float, rp: float) -> tuple[tuple[Body, ...], tuple[Revolute | GearPair, ...]]:
    """A planetary train whose sun and arm both turn about the origin, the planet pinned on the arm:
    the gear law ties three moving angles. Bodies and joints; the caller adds the drivers."""
    arm = rs + rp
    bodies = (
        Body("sun", (0.0, 0.0, 0.0), mass=0.1, inertia=1e-4),
        Body("arm", (arm / 2, 0.0, 0.0), mass=0.1, inertia=1e-4, length=arm),
        Body("planet", (arm, 0.0, 0.0), mass=0.05, inertia=1e-5),
    )
    joints = (
        Revolute("sun_pivot", Point(GROUND), Point("sun")),
        Revolute("arm_pivot", Point(GROUND), Point("arm", (-arm / 2, 0.0))),
        Revolute("planet_pivot", Point("arm", (arm / 2, 0.0)), Point("planet")),
        GearPair("mesh", "sun", rs, "planet", rp, carrier="arm"),
    )
    return bodies, joints
