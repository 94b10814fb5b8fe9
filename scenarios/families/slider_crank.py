"""Slider-crank: crank O-A pinned to the ground at O, rod A-B, slider pinned at B on the line y = offset.

Driven by the crank at constant speed, or by the slider along a prescribed harmonic x(t) that starts
mid-stroke and sweeps `stroke_fraction` of the way between its dead centres.
Closed form: l2 sin th2 + l3 sin th3 = h, x_B = l2 cos th2 + l3 cos th3.
"""

from __future__ import annotations

import math

import numpy as np

from scenarios.bodies import GROUND, Body, Point
from scenarios.drivers import AbsoluteDriver
from scenarios.family import Family, angle, choice, length, offset, positive, speed, time_grid
from scenarios.joints import Prismatic, Revolute
from scenarios.link_kinematics import assemble, constant_speed, fixed, frame, link_point, solve2
from scenarios.motions import ConstantSpeed, Harmonic
from scenarios.scenario import (
    ParameterValue,
    Scenario,
    ScenarioError,
    revolving,
)
from scenarios.trajectory import Trajectory


def stroke_limits(l2: float, l3: float, h: float) -> tuple[float, float]:
    """The slider's x at the outer and inner dead centres (crank and rod aligned)."""
    outer = math.sqrt((l2 + l3) ** 2 - h**2)
    inner = math.sqrt((l3 - l2) ** 2 - h**2) if abs(h) < abs(l3 - l2) else -outer
    return outer, inner


def _build(p: dict[str, ParameterValue], variant: str) -> Scenario:
    l2, l3, h = float(p["crank_length"]), float(p["rod_length"]), float(p["offset"])
    omega, theta0 = float(p["omega"]), float(p["theta0"])
    drive = str(p["drive"])
    if abs(h) >= l2 + l3:
        raise ScenarioError(
            f"slider_crank: |offset| {abs(h)} must be below crank_length + rod_length {l2 + l3}"
        )

    # Rough guess: crank at theta0, rod angle from the closure of the y-coordinates.
    s3 = max(-1.0, min(1.0, (h - l2 * math.sin(theta0)) / l3))
    th3 = math.asin(s3)
    ax, ay = l2 * math.cos(theta0), l2 * math.sin(theta0)
    bx = ax + l3 * math.cos(th3)
    bodies = (
        Body("crank", (ax / 2, ay / 2, theta0), mass=l2, inertia=l2**3 / 12, length=l2),
        Body("rod", ((ax + bx) / 2, (ay + h) / 2, th3), mass=l3, inertia=l3**3 / 12, length=l3),
        # The slider scales with the crank (0.5 kg at the default 0.2 m), so that a scaled mechanism is
        # also similar in its dynamics.
        Body("slider", (bx, h, 0.0), mass=2.5 * l2, inertia=1e-4 * (l2 / 0.2) ** 3),
    )
    joints = (
        Revolute("O", Point(GROUND, (0.0, 0.0)), Point("crank", (-l2 / 2, 0.0))),
        Revolute("A", Point("crank", (l2 / 2, 0.0)), Point("rod", (-l3 / 2, 0.0))),
        Revolute("B", Point("rod", (l3 / 2, 0.0)), Point("slider")),
        Prismatic("slide", Point("slider"), Point(GROUND, (0.0, h)), axis=(1.0, 0.0), angle=0.0),
    )
    if drive == "crank":
        driver = AbsoluteDriver("crank_drive", "crank", "theta", ConstantSpeed(theta0, omega))
    else:
        outer, inner = stroke_limits(l2, l3, h)
        fraction = float(p["stroke_fraction"])
        mean, half = (outer + inner) / 2, fraction * (outer - inner) / 2
        # x = mean + half sin(omega t): from mid-stroke outwards, so a stroke_fraction >= 1 reaches the
        # outer dead centre at t = asin(1 / stroke_fraction) / omega.
        motion = Harmonic(mean, half, abs(omega), phase=-math.pi / 2)
        driver = AbsoluteDriver("slider_drive", "slider", "x", motion)
    return revolving(
        "slider_crank", variant, p, bodies, joints, (driver,), l2, f"slider-crank driven by the {drive}"
    )


def closed_form(s: Scenario, t: np.ndarray) -> Trajectory:
    """The slider-crank's exact kinematics (module docstring): crank-driven, the rod's angle from the
    y closure; slider-driven, the crank's from the triangle O-A-B; rates by Cramer's rule."""
    l2, l3, h = (float(s.parameter(k)) for k in ("crank_length", "rod_length", "offset"))
    n = len(t)
    if s.parameter("drive") == "crank":
        th2, w2, a2 = constant_speed(s, t)
        th3 = np.arcsin((h - l2 * np.sin(th2)) / l3)
        w3 = -l2 * np.cos(th2) * w2 / (l3 * np.cos(th3))
        a3 = (l2 * np.sin(th2) * w2**2 - l2 * np.cos(th2) * a2 + l3 * np.sin(th3) * w3**2) / (
            l3 * np.cos(th3)
        )
    else:
        outer, inner = stroke_limits(l2, l3, h)
        mean, half = (outer + inner) / 2, float(s.parameter("stroke_fraction")) * (outer - inner) / 2
        om = abs(float(s.parameter("omega")))
        xb, vb, ab = mean + half * np.sin(om * t), half * om * np.cos(om * t), -half * om**2 * np.sin(om * t)
        rho = np.hypot(xb, h)
        th2 = np.arctan2(h, xb) + np.arccos((rho**2 + l2**2 - l3**2) / (2 * l2 * rho))
        th3 = np.arctan2(h - l2 * np.sin(th2), xb - l2 * np.cos(th2))
        # x_B = l2 cos th2 + l3 cos th3 and h = l2 sin th2 + l3 sin th3, differentiated.
        m = (-l2 * np.sin(th2), -l3 * np.sin(th3), l2 * np.cos(th2), l3 * np.cos(th3))
        w2, w3 = solve2(*m, vb, np.zeros(n))
        r1 = ab + l2 * np.cos(th2) * w2**2 + l3 * np.cos(th3) * w3**2
        r2 = l2 * np.sin(th2) * w2**2 + l3 * np.sin(th3) * w3**2
        a2, a3 = solve2(*m, r1, r2)
    origin = fixed(n, 0.0, 0.0)
    a_pin = link_point(origin, th2, w2, a2, l2)
    b_pin = link_point(a_pin, th3, w3, a3, l3)
    zero = np.zeros(n)
    return assemble(
        t,
        {
            "crank": frame(link_point(origin, th2, w2, a2, l2 / 2), th2, w2, a2),
            "rod": frame(link_point(a_pin, th3, w3, a3, l3 / 2), th3, w3, a3),
            "slider": frame(b_pin, zero, zero, zero),
        },
    )


FAMILY = Family(
    name="slider_crank",
    summary="crank, rod and slider; crank- or slider-driven, optional offset",
    parameters={
        "crank_length": length(0.2),
        "rod_length": length(0.4),
        "offset": offset(0.0),
        "omega": speed(50.0),
        "theta0": angle(0.3),
        "drive": choice("crank", "slider"),
        "stroke_fraction": positive(0.9, 10.0),
        **time_grid(),
    },
    build=_build,
    closed_form=closed_form,
    variants={
        "offset": {"offset": 0.05},
        "slider_drive": {"drive": "slider", "theta0": 1.2},
        "slider_drive_offset": {"drive": "slider", "offset": 0.05, "theta0": 1.2},
        # Stress variants (the stress suite; reports/stress/cases.py says what each probes).
        # Singular: the outer dead centre at t = pi / (2 omega); equal crank and rod at th2 = pi/2.
        "stress_dead_centre": {"drive": "slider", "theta0": 1.2, "stroke_fraction": 1.0},
        "stress_equal_links": {"rod_length": 0.2},
        # Speeds at 200 steps per revolution, and at the nominal grid step of 2 pi / 50 / 200 s.
        "stress_speed_1e-3": {"omega": 1e-3},
        "stress_speed_1e-1": {"omega": 1e-1},
        "stress_speed_1e1": {"omega": 1e1},
        "stress_speed_1e3": {"omega": 1e3},
        "stress_speed_1e4": {"omega": 1e4},
        "stress_fixed_step_1e-3": {"omega": 1e-3, "revolutions": 1e-4, "steps": 1000},
        "stress_fixed_step_1e2": {"omega": 1e2, "revolutions": 1.0, "steps": 100},
        "stress_fixed_step_1e3": {"omega": 1e3, "revolutions": 5.0, "steps": 50},
        "stress_fixed_step_1e4": {"omega": 1e4, "revolutions": 10.0, "steps": 10},
        # Scales: the nominal mechanism with its crank 1e-4 m to 1e3 m long.
        "stress_scale_1e-4": {"crank_length": 1e-4, "rod_length": 2e-4},
        "stress_scale_1e-2": {"crank_length": 1e-2, "rod_length": 2e-2},
        "stress_scale_1e1": {"crank_length": 1e1, "rod_length": 2e1},
        "stress_scale_1e3": {"crank_length": 1e3, "rod_length": 2e3},
        "stress_link_ratio_1e-3": {"crank_length": 4e-4, "rod_length": 0.4},
        "stress_long": {"revolutions": 1000.0, "steps": 20000},
        "stress_stiffness": {"steps": 20},
    },
)
