"""Four-bar linkage: crank O2-A, coupler A-B, rocker O4-B, ground pivots O2 = (0, 0), O4 = (g, 0).

A Grashof crank-rocker by default, driven by the crank at constant speed; `branch` +1 assembles B
above the line A-O4 (the open configuration), -1 below (the crossed one). `mass_ratio` multiplies the
coupler's mass and inertia (a kinematically driven result must not depend on it).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from scenarios.bodies import GROUND, Body, Point
from scenarios.drivers import AbsoluteDriver
from scenarios.family import Family, Parameter, angle, length, positive, speed, time_grid
from scenarios.joints import Revolute
from scenarios.link_kinematics import assemble, constant_speed, fixed, frame, link_point, solve2
from scenarios.motions import ConstantSpeed
from scenarios.scenario import (
    ParameterValue,
    Scenario,
    revolving,
)
from scenarios.trajectory import Trajectory


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


ROUND_OFF = 8 * float(np.finfo(float).eps)
"""How far past 1 the cosine of a closing triangle may come by round-off alone (at a dead point)."""


def _closing_cosine(b: float, c: float, d: np.ndarray) -> np.ndarray:
    """The cosine of the coupler's angle to the diagonal d of the triangle (b, c, d): clipped to
    [-1, 1] within round-off, NaN where the triangle does not close (the crank past a dead point),
    without a floating-point warning."""
    cosine = (b**2 + d**2 - c**2) / (2 * b * d)
    return np.where(np.abs(cosine) <= 1.0 + ROUND_OFF, np.clip(cosine, -1.0, 1.0), np.nan)


def closed_form(s: Scenario, t: np.ndarray) -> Trajectory:
    """The four-bar's exact kinematics: the coupler's angle from the triangle A-B-O4 on `branch`, the
    rocker's from B; rates from a e2 + b e3 - c e4 = (g, 0) differentiated, by Cramer's rule."""
    g, a, b, c = (
        float(s.parameter(k)) for k in ("ground_length", "crank_length", "coupler_length", "rocker_length")
    )
    branch = int(s.parameter("branch"))
    n = len(t)
    th2, w2, a2 = constant_speed(s, t)
    ax, ay = a * np.cos(th2), a * np.sin(th2)
    dx, dy = g - ax, -ay
    d = np.hypot(dx, dy)
    th3 = np.unwrap(np.arctan2(dy, dx) + branch * np.arccos(_closing_cosine(b, c, d)))
    bx, by = ax + b * np.cos(th3), ay + b * np.sin(th3)
    th4 = np.unwrap(np.arctan2(by, bx - g))
    # a e2 + b e3 - c e4 = (g, 0), differentiated: b w3 e3' - c w4 e4' = -a w2 e2'.
    m = (-b * np.sin(th3), c * np.sin(th4), b * np.cos(th3), -c * np.cos(th4))
    w3, w4 = solve2(*m, a * np.sin(th2) * w2, -a * np.cos(th2) * w2)
    r1 = a * np.sin(th2) * a2 + a * np.cos(th2) * w2**2 + b * np.cos(th3) * w3**2 - c * np.cos(th4) * w4**2
    r2 = -a * np.cos(th2) * a2 + a * np.sin(th2) * w2**2 + b * np.sin(th3) * w3**2 - c * np.sin(th4) * w4**2
    a3, a4 = solve2(*m, r1, r2)
    origin, o4 = fixed(n, 0.0, 0.0), fixed(n, g, 0.0)
    a_pin = link_point(origin, th2, w2, a2, a)
    return assemble(
        t,
        {
            "crank": frame(link_point(origin, th2, w2, a2, a / 2), th2, w2, a2),
            "coupler": frame(link_point(a_pin, th3, w3, a3, b / 2), th3, w3, a3),
            "rocker": frame(link_point(o4, th4, w4, a4, c / 2), th4, w4, a4),
        },
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
    closed_form=closed_form,
    variants={
        "crossed": {"branch": -1},
        # Stress variants (the stress suite; reports/stress/cases.py says what each probes).
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
