"""Rack and pinion: a pinion pinned at the origin and driven at constant speed moves a rack that
slides along x below it. The rack's frame sits on its pitch line under the pinion's centre at t = 0;
the rack travels radius * (theta - theta0)."""

from __future__ import annotations

import numpy as np

from scenarios.bodies import GROUND, Body, Point
from scenarios.drivers import AbsoluteDriver
from scenarios.families.spur_gears import gear_body
from scenarios.family import Family, angle, length, speed, time_grid
from scenarios.gears import RackPinion
from scenarios.joints import Prismatic, Revolute
from scenarios.link_kinematics import assemble, constant_speed, fixed, frame
from scenarios.motions import ConstantSpeed
from scenarios.scenario import (
    ParameterValue,
    Scenario,
    revolving,
)
from scenarios.trajectory import Trajectory


def _build(p: dict[str, ParameterValue], variant: str) -> Scenario:
    r, omega, theta0 = float(p["radius"]), float(p["omega"]), float(p["theta0"])
    bodies = (gear_body("pinion", (0.0, 0.0), r, theta0), Body("rack", (0.0, -r, 0.0), mass=1.0))
    joints = (
        Revolute("pivot", Point(GROUND, (0.0, 0.0)), Point("pinion")),
        Prismatic("guide", Point("rack"), Point(GROUND, (0.0, -r)), axis=(1.0, 0.0), angle=0.0),
        RackPinion("mesh", Point("pinion"), r, Point("rack"), axis=(1.0, 0.0), offset=-r * theta0),
    )
    driver = AbsoluteDriver("drive", "pinion", "theta", ConstantSpeed(theta0, omega))
    description = "pinion on fixed centre driving a sliding rack"
    return revolving("rack_pinion", variant, p, bodies, joints, (driver,), r, description)


def closed_form(s: Scenario, t: np.ndarray) -> Trajectory:
    """The pinion at the drive's angle, the rack travelling radius * (theta - theta0) along x."""
    r = float(s.parameter("radius"))
    th, w, al = constant_speed(s, t)
    theta0 = float(s.parameter("theta0"))
    n = len(t)
    zero = np.zeros(n)
    rack = (
        np.column_stack([r * (th - theta0), np.full(n, -r)]),
        np.column_stack([r * w, zero]),
        np.column_stack([r * al, zero]),
    )
    return assemble(
        t, {"pinion": frame(fixed(n, 0.0, 0.0), th, w, al), "rack": frame(rack, zero, zero, zero)}
    )


FAMILY = Family(
    name="rack_pinion",
    summary="driven pinion and sliding rack",
    parameters={"radius": length(0.05), "omega": speed(10.0), "theta0": angle(0.0), **time_grid()},
    build=_build,
    closed_form=closed_form,
    variants={},
)
