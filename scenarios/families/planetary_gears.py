"""Planetary train with a fixed sun: the arm turns about the sun's centre and carries the planet.

The sun is the ground (radius_sun), the planet (radius_planet) meshes externally with it and is
pinned to the arm's end. The planet turns at omega_arm (1 + r_sun / r_planet).
"""

from __future__ import annotations

import math

import numpy as np

from scenarios.bodies import GROUND, Point
from scenarios.drivers import AbsoluteDriver
from scenarios.families.four_bar import link
from scenarios.families.spur_gears import gear_body
from scenarios.family import Family, angle, length, speed, time_grid
from scenarios.gears import GearPair
from scenarios.joints import Revolute
from scenarios.link_kinematics import assemble, constant_speed, fixed, frame, link_point
from scenarios.motions import ConstantSpeed
from scenarios.scenario import (
    ParameterValue,
    Scenario,
    revolving,
)
from scenarios.trajectory import Trajectory


def _build(p: dict[str, ParameterValue], variant: str) -> Scenario:
    rs, rp = float(p["radius_sun"]), float(p["radius_planet"])
    omega, theta0 = float(p["omega"]), float(p["theta0"])
    arm_length = rs + rp
    end = (arm_length * math.cos(theta0), arm_length * math.sin(theta0))
    bodies = (link("arm", (0.0, 0.0), end, arm_length), gear_body("planet", end, rp, 0.0))
    joints = (
        Revolute("arm_pivot", Point(GROUND, (0.0, 0.0)), Point("arm", (-arm_length / 2, 0.0))),
        Revolute("planet_pivot", Point("arm", (arm_length / 2, 0.0)), Point("planet")),
        GearPair("mesh", GROUND, rs, "planet", rp, carrier="arm", theta0_carrier=theta0),
    )
    driver = AbsoluteDriver("arm_drive", "arm", "theta", ConstantSpeed(theta0, omega))
    description = "planetary train: fixed sun, driven arm, one planet"
    return revolving("planetary_gears", variant, p, bodies, joints, (driver,), arm_length, description)


def closed_form(s: Scenario, t: np.ndarray) -> Trajectory:
    """The arm at the drive's angle, the planet on its end turning at (1 + r_sun / r_planet) times it."""
    rs, rp = float(s.parameter("radius_sun")), float(s.parameter("radius_planet"))
    th, w, al = constant_speed(s, t)
    theta0 = float(s.parameter("theta0"))
    origin = fixed(len(t), 0.0, 0.0)
    ratio = 1.0 + rs / rp
    return assemble(
        t,
        {
            "arm": frame(link_point(origin, th, w, al, (rs + rp) / 2), th, w, al),
            "planet": frame(
                link_point(origin, th, w, al, rs + rp), ratio * (th - theta0), ratio * w, ratio * al
            ),
        },
    )


FAMILY = Family(
    name="planetary_gears",
    summary="fixed sun, driven arm and a planet",
    parameters={
        "radius_sun": length(0.06),
        "radius_planet": length(0.03),
        "omega": speed(10.0),
        "theta0": angle(0.0),
        **time_grid(),
    },
    build=_build,
    closed_form=closed_form,
    variants={},
)
