"""Compound pendulum under gravity: `links` uniform rods hanging from a ground pivot at the origin,
each pinned to the tip of the one before; a tree with no loop, the control case of the dynamic tier.
The default is the compound double pendulum; `links` 1 is the physical pendulum whose small
oscillations have the closed form theta(t) = theta0 cos(sqrt(3 g / (2 l)) t) about the hanging
position.
"""

from __future__ import annotations

import math

from scenarios.bodies import GROUND, Body, Point
from scenarios.family import MAX_GRID_STEPS, Family, Parameter, angle, count, length, positive
from scenarios.joints import Revolute
from scenarios.scenario import ParameterValue, Scenario, ScenarioError, require_finite, require_positive


def _build(p: dict[str, ParameterValue], variant: str) -> Scenario:
    links, length, mass = int(p["links"]), float(p["link_length"]), float(p["link_mass"])
    theta0, gravity = float(p["theta0"]), float(p["gravity"])
    require_positive("compound_pendulum", link_length=length, link_mass=mass, t_end=float(p["t_end"]))
    require_finite("compound_pendulum", theta0=theta0, gravity=gravity)
    if links < 1:
        raise ScenarioError(f"compound_pendulum: links must be at least 1, got {links}")
    # theta0 is each link's angle from the downward vertical; body angles are measured from +x.
    angle = theta0 - math.pi / 2
    bodies, joints = [], []
    tip = (0.0, 0.0)
    for k in range(links):
        name = f"link_{k + 1}"
        mid = (tip[0] + 0.5 * length * math.cos(angle), tip[1] + 0.5 * length * math.sin(angle))
        bodies.append(Body(name, (*mid, angle), mass=mass, inertia=mass * length**2 / 12, length=length))
        previous = Point(GROUND, tip) if k == 0 else Point(f"link_{k}", (length / 2, 0.0))
        joints.append(Revolute(f"pin_{k + 1}", previous, Point(name, (-length / 2, 0.0))))
        tip = (tip[0] + length * math.cos(angle), tip[1] + length * math.sin(angle))
    return Scenario(
        family="compound_pendulum",
        variant=variant,
        bodies=tuple(bodies),
        joints=tuple(joints),
        drivers=(),
        t_end=float(p["t_end"]),
        steps=int(p["steps"]),
        characteristic_length=length,
        parameters=tuple(p.items()),
        description=f"compound pendulum of {links} uniform links released from rest under gravity",
        gravity=(0.0, -gravity),
        analysis="dynamic",
    )


FAMILY = Family(
    name="compound_pendulum",
    summary="uniform links hanging in a chain under gravity (the compound double pendulum by default)",
    parameters={
        "links": count(2, 1, 1000),
        "link_length": length(0.5),
        "link_mass": positive(1.0, 1e9, "kg"),
        "theta0": angle(1.0),
        "gravity": Parameter(9.81, "m/s^2", low=-1e6, high=1e6),
        "t_end": positive(2.0, 1e6, "s"),
        "steps": count(200, 1, MAX_GRID_STEPS),
    },
    build=_build,
    variants={"small_oscillation": {"links": 1, "theta0": 1e-4}},
    dynamic=True,
)
