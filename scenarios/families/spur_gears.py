"""Two spur gears on fixed centres: the input gear at the origin is driven at constant speed.

External mesh: centres radius_in + radius_out apart, the output turns at -omega r_in / r_out.
Internal mesh: the output is a ring of radius_out > radius_in, centres radius_out - radius_in
apart, and it turns at +omega r_in / r_out.
"""

from __future__ import annotations

import math

import numpy as np

from scenarios.bodies import GROUND, Body, Point
from scenarios.drivers import AbsoluteDriver
from scenarios.family import Family, angle, choice, length, speed, time_grid
from scenarios.gears import GearPair
from scenarios.joints import Revolute
from scenarios.link_kinematics import assemble, constant_speed, fixed, frame
from scenarios.motions import ConstantSpeed
from scenarios.scenario import (
    ParameterValue,
    Scenario,
    ScenarioError,
    revolving,
)
from scenarios.trajectory import Trajectory


def gear_body(name: str, centre: tuple[float, float], radius: float, angle: float) -> Body:
    """A gear disc (unit areal density) with its frame at its centre."""
    mass = math.pi * radius**2
    return Body(name, (centre[0], centre[1], angle), mass=mass, inertia=mass * radius**2 / 2)


def _build(p: dict[str, ParameterValue], variant: str) -> Scenario:
    r1, r2 = float(p["radius_in"]), float(p["radius_out"])
    omega, theta0, mesh = float(p["omega"]), float(p["theta0"]), str(p["mesh"])
    internal = mesh == "internal"
    if internal and r2 <= r1:
        raise ScenarioError(f"spur_gears: an internal mesh needs radius_out > radius_in, got {r2} <= {r1}")
    distance = r2 - r1 if internal else r1 + r2
    bodies = (
        gear_body("gear_in", (0.0, 0.0), r1, theta0),
        gear_body("gear_out", (distance, 0.0), r2, 0.0),
    )
    joints = (
        Revolute("pivot_in", Point(GROUND, (0.0, 0.0)), Point("gear_in")),
        Revolute("pivot_out", Point(GROUND, (distance, 0.0)), Point("gear_out")),
        GearPair("mesh", "gear_in", r1, "gear_out", r2, internal=internal, theta0_i=theta0),
    )
    driver = AbsoluteDriver("drive", "gear_in", "theta", ConstantSpeed(theta0, omega))
    return revolving(
        "spur_gears", variant, p, bodies, joints, (driver,), r1, f"spur gear pair, {mesh} mesh, fixed centres"
    )


def closed_form(s: Scenario, t: np.ndarray) -> Trajectory:
    """Both gears on their fixed centres, the output turning at -+ r_in / r_out times the input."""
    r1, r2 = float(s.parameter("radius_in")), float(s.parameter("radius_out"))
    internal = s.parameter("mesh") == "internal"
    th, w, al = constant_speed(s, t)
    ratio = (r1 / r2) if internal else -(r1 / r2)
    theta0 = float(s.parameter("theta0"))
    n = len(t)
    centre = r2 - r1 if internal else r1 + r2
    return assemble(
        t,
        {
            "gear_in": frame(fixed(n, 0.0, 0.0), th, w, al),
            "gear_out": frame(fixed(n, centre, 0.0), ratio * (th - theta0), ratio * w, ratio * al),
        },
    )


FAMILY = Family(
    name="spur_gears",
    summary="two spur gears on fixed centres, external or internal mesh",
    parameters={
        "radius_in": length(0.05),
        "radius_out": length(0.15),
        "omega": speed(10.0),
        "theta0": angle(0.0),
        "mesh": choice("external", "internal"),
        **time_grid(),
    },
    build=_build,
    closed_form=closed_form,
    variants={
        "internal": {"mesh": "internal"},
        "stress_ratio_1000": {"radius_in": 1e-3, "radius_out": 1.0},  # the stress suite: 1:1000
    },
)
