"""Rack and pinion: a pinion pinned at the origin and driven at constant speed moves a rack that
slides along x below it. The rack's frame sits on its pitch line under the pinion's centre at t = 0;
the rack travels radius * (theta - theta0)."""

from __future__ import annotations

from scenarios.bodies import GROUND, Body, Point
from scenarios.drivers import AbsoluteDriver
from scenarios.gears import RackPinion
from scenarios.joints import Prismatic, Revolute
from scenarios.motions import ConstantSpeed
from scenarios.registry import Family
from scenarios.scenario import (
    ParameterValue,
    Scenario,
    ScenarioError,
    require_finite,
    require_positive,
    revolving,
)
from scenarios.spur_gears import gear_body


def _build(p: dict[str, ParameterValue], variant: str) -> Scenario:
    r, omega, theta0 = float(p["radius"]), float(p["omega"]), float(p["theta0"])
    require_positive("rack_pinion", radius=r, revolutions=float(p["revolutions"]))
    require_finite("rack_pinion", omega=omega, theta0=theta0)
    if omega == 0.0:
        raise ScenarioError("rack_pinion: omega must be non-zero")
    bodies = (gear_body("pinion", (0.0, 0.0), r, theta0), Body("rack", (0.0, -r, 0.0), mass=1.0))
    joints = (
        Revolute("pivot", Point(GROUND, (0.0, 0.0)), Point("pinion")),
        Prismatic("guide", Point("rack"), Point(GROUND, (0.0, -r)), axis=(1.0, 0.0), angle=0.0),
        RackPinion("mesh", Point("pinion"), r, Point("rack"), axis=(1.0, 0.0), offset=-r * theta0),
    )
    driver = AbsoluteDriver("drive", "pinion", "theta", ConstantSpeed(theta0, omega))
    description = "pinion on fixed centre driving a sliding rack"
    return revolving(
        "rack_pinion",
        variant,
        p,
        bodies,
        joints,
        (driver,),
        r,
        description,
    )


FAMILY = Family(
    name="rack_pinion",
    summary="driven pinion and sliding rack",
    defaults={"radius": 0.05, "omega": 10.0, "theta0": 0.0, "revolutions": 1.0, "steps": 200},
    build=_build,
    variants={},
)
