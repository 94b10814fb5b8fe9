"""Four-bar linkage: crank O2-A, coupler A-B, rocker O4-B, ground pivots O2 = (0, 0), O4 = (g, 0).

A Grashof crank-rocker by default, driven by the crank at constant speed; `branch` +1 assembles B
above the line A-O4 (the open configuration), -1 below (the crossed one). `mass_ratio` multiplies the
coupler's mass and inertia (a kinematically driven result must not depend on it).
"""

from __future__ import annotations

import math
from dataclasses import replace

from scenarios.bodies import GROUND, Body, Point
from scenarios.drivers import AbsoluteDriver
from scenarios.family import Family, Parameter, angle, length, positive, speed, time_grid
from scenarios.joints import Revolute
from scenarios.motions import ConstantSpeed
from scenarios.scenario import (
    ParameterValue,
    Scenario,
    revolving,
)


def link(name: str, start: tuple[float, float], end: tuple[float, float], length: float) -> Body:
    """A link body with its frame at the midpoint, x from `start` to `end` (a rough guess)."""
    angle = math.atan2(end[1] - start[1], end[0] - start[0])
    mid = ((start[0] + end[0]) / 2, (start[1] + end[1]) / 2, angle)
    return Body(name, mid, mass=length, inertia=length**3 / 12, length=length)


def _build(p: dict[str, ParameterValue], variant: str) -> Scenario:
    g, a = float(p["ground_length"]), float(p["crank_length"])
    b, c = float(p["coupler_length"]), float(p["rocker_length"])
    omega, theta0, branch = float(p["omega"]), float(p["theta0"]), int(p["branch"])
    mass_ratio = float(p["mass_ratio"])

    ax, ay = a * math.cos(theta0), a * math.sin(theta0)
    dx, dy = g - ax, -ay
    d = math.hypot(dx, dy)
    cos_gamma = max(-1.0, min(1.0, (b * b + d * d - c * c) / (2 * b * d)))
    angle = math.atan2(dy, dx) + branch * math.acos(cos_gamma)
    bx, by = ax + b * math.cos(angle), ay + b * math.sin(angle)
    coupler = link("coupler", (ax, ay), (bx, by), b)
    coupler = replace(coupler, mass=coupler.mass * mass_ratio, inertia=coupler.inertia * mass_ratio)
    bodies = (link("crank", (0.0, 0.0), (ax, ay), a), coupler, link("rocker", (g, 0.0), (bx, by), c))
    joints = (
        Revolute("O2", Point(GROUND, (0.0, 0.0)), Point("crank", (-a / 2, 0.0))),
        Revolute("A", Point("crank", (a / 2, 0.0)), Point("coupler", (-b / 2, 0.0))),
        Revolute("B", Point("coupler", (b / 2, 0.0)), Point("rocker", (c / 2, 0.0))),
        Revolute("O4", Point(GROUND, (g, 0.0)), Point("rocker", (-c / 2, 0.0))),
    )
    driver = AbsoluteDriver("crank_drive", "crank", "theta", ConstantSpeed(theta0, omega))
    return revolving(
        "four_bar", variant, p, bodies, joints, (driver,), a, "four-bar linkage driven by the crank"
    )


FAMILY = Family(
    name="four_bar",
    summary="crank, coupler and rocker; a Grashof crank-rocker by default",
    parameters={
        "ground_length": length(0.1),
        "crank_length": length(0.05),
        "coupler_length": length(0.1),
        "rocker_length": length(0.125),
        "omega": speed(50.0),
        "theta0": angle(0.3),
        "branch": Parameter(1, low=-1, high=1, nonzero=True),
        "mass_ratio": positive(1.0, 1e12),
        **time_grid(),
    },
    build=_build,
    variants={
        "crossed": {"branch": -1},
        # Stress variants (the stress suite; reports/stress_cases.py says what each probes).
        # Change point, s + l = p + q: all links aligned at th2 = pi. Near it: 1e-6 m short of it.
        "stress_change_point": {"crank_length": 0.04, "coupler_length": 0.08, "rocker_length": 0.06},
        "stress_near_change_point": {"crank_length": 0.04, "coupler_length": 0.08, "rocker_length": 0.060001},
        # Coupler and rocker stretch into line (toggle) at cos th2 = (a^2 + g^2 - (b + c)^2) / (2 a g).
        "stress_toggle": {"crank_length": 0.06, "coupler_length": 0.05, "rocker_length": 0.08},
        "stress_link_ratio_1e-3": {"crank_length": 1e-4, "coupler_length": 0.1, "rocker_length": 0.1},
        "stress_mass_1e3": {"mass_ratio": 1e3},
        "stress_mass_1e6": {"mass_ratio": 1e6},
    },
)
