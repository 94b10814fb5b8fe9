"""Closed-form kinematics of every mechanism family, derived independently of the native solver.

Angles come from the classical geometric solutions (triangle closures, inverse trigonometry); rates
from differentiating the loop equations by hand (2x2 systems solved by Cramer's rule). Each
returns a Trajectory of every body of the scenario, all three levels, and the contact parameter
phi of cams as the extra `contact.phi` (positions only). A closed form is given only for the
mechanism the family builds (`exact`): the truth is never another mechanism's.
"""

from __future__ import annotations

import math

import numpy as np

from scenarios import Scenario, Trajectory
from scenarios.families.slider_crank import stroke_limits
from scenarios.identity import family_twin
from scenarios.link_kinematics import assemble, constant_speed, fixed, frame, link_point, solve2, unit


def slider_crank(s: Scenario, t: np.ndarray) -> Trajectory:
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


def four_bar(s: Scenario, t: np.ndarray) -> Trajectory:
    g, a, b, c = (
        float(s.parameter(k)) for k in ("ground_length", "crank_length", "coupler_length", "rocker_length")
    )
    branch = int(s.parameter("branch"))
    n = len(t)
    th2, w2, a2 = constant_speed(s, t)
    ax, ay = a * np.cos(th2), a * np.sin(th2)
    dx, dy = g - ax, -ay
    d = np.hypot(dx, dy)
    th3 = np.unwrap(np.arctan2(dy, dx) + branch * np.arccos((b**2 + d**2 - c**2) / (2 * b * d)))
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


def spur_gears(s: Scenario, t: np.ndarray) -> Trajectory:
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


def planetary_gears(s: Scenario, t: np.ndarray) -> Trajectory:
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


def rack_pinion(s: Scenario, t: np.ndarray) -> Trajectory:
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


def disc_cam(s: Scenario, t: np.ndarray) -> Trajectory:
    big_r, e = float(s.parameter("radius")), float(s.parameter("eccentricity"))
    th, w, al = constant_speed(s, t)
    n = len(t)
    zero = np.zeros(n)
    centre = e * unit(th)  # the disc's centre, global
    if s.family == "cam_flat_face":
        y, dy, ddy = big_r + e * np.sin(th), e * np.cos(th), -e * np.sin(th)
        contact = centre + np.array([0.0, big_r])
    else:
        rr = float(s.parameter("roller_radius")) if s.family == "cam_roller" else 0.0
        g = (big_r + rr) ** 2 - (e * np.cos(th)) ** 2
        y = e * np.sin(th) + np.sqrt(g)
        dy = e * np.cos(th) + e**2 * np.sin(2 * th) / (2 * np.sqrt(g))
        ddy = (
            -e * np.sin(th) + e**2 * np.cos(2 * th) / np.sqrt(g) - (e**2 * np.sin(2 * th)) ** 2 / (4 * g**1.5)
        )
        follower = np.column_stack([zero, y])
        contact = centre + big_r * (follower - centre) / np.linalg.norm(follower - centre, axis=1)[:, None]
    # phi: the polar angle of the contact point in the cam's frame.
    phi = np.unwrap(np.arctan2(contact[:, 1], contact[:, 0]) - th)
    phi += 2 * math.pi * round((math.pi / 2 - th[0] - phi[0]) / (2 * math.pi))
    follower_kin = (
        np.column_stack([zero, y]),
        np.column_stack([zero, dy * w]),
        np.column_stack([zero, ddy * w**2 + dy * al]),
    )
    return assemble(
        t,
        {"cam": frame(fixed(n, 0.0, 0.0), th, w, al), "follower": frame(follower_kin, zero, zero, zero)},
        extras={"contact.phi": phi},
    )


def four_bar_chain(scenario: Scenario, t: np.ndarray) -> Trajectory:
    """Every rocker turns with the crank, theta = theta0 + A sin(omega t); every coupler translates:
    rocker k's frame at (k g, 0) + L/2 e(theta), coupler k's at ((k - 1/2) g, 0) + L e(theta)."""
    p = dict(scenario.parameters)
    loops, length, g = int(p["loops"]), float(p["link_length"]), float(p["coupler_length"])
    omega, amplitude, theta0 = float(p["omega"]), float(p["amplitude"]), float(p["theta0"])
    theta = theta0 + amplitude * np.sin(omega * t)
    rate = amplitude * omega * np.cos(omega * t)
    accel = -amplitude * omega**2 * np.sin(omega * t)
    e, n = np.stack([np.cos(theta), np.sin(theta)], -1), np.stack([-np.sin(theta), np.cos(theta)], -1)
    zero = np.zeros_like(t)

    def body(base_x: float, reach: float, turns: bool):  # type: ignore[no-untyped-def]
        angle = (theta, rate, accel) if turns else (zero, zero, zero)
        pos = np.column_stack([base_x + reach * e[:, 0], reach * e[:, 1], angle[0]])
        vel = np.column_stack([reach * rate[:, None] * n, angle[1]])
        acc = np.column_stack([reach * (accel[:, None] * n - rate[:, None] ** 2 * e), angle[2]])
        return pos, vel, acc

    parts = [body(0.0, length / 2, True)]
    for k in range(1, loops + 1):
        parts += [body((k - 0.5) * g, length, False), body(k * g, length / 2, True)]
    position, velocity, acceleration = (
        np.stack([part[level] for part in parts], axis=1) for level in range(3)
    )
    return Trajectory(t, scenario.body_names, position, velocity, acceleration)


FAMILIES = {
    "slider_crank": slider_crank,
    "four_bar": four_bar,
    "spur_gears": spur_gears,
    "planetary_gears": planetary_gears,
    "rack_pinion": rack_pinion,
    "cam_knife_edge": disc_cam,
    "cam_roller": disc_cam,
    "cam_flat_face": disc_cam,
    "four_bar_chain": four_bar_chain,
}


class NoClosedForm(ValueError):
    """The scenario has no closed form: it is not a family's own mechanism, or its family has none."""


def exact(scenario: Scenario, times: np.ndarray | list[float] | None = None) -> Trajectory:
    """The closed-form trajectory of `scenario` (eccentric disc profiles only for cams).

    Only a family's own mechanism has one: `scenario` must be what the family builds from the
    parameters it records (scenarios.identity.family_twin, by digest). A file that takes a family's
    name, or an export edited after it was written, is another mechanism, whatever its
    `[parameters]` table says, and gets NoClosedForm."""
    if scenario.family not in FAMILIES:
        raise NoClosedForm(f"{scenario.name}: no closed form: not a family with one")
    twin = family_twin(scenario)
    if twin is None:
        raise NoClosedForm(
            f"{scenario.name}: no closed form: not the mechanism the family {scenario.family} builds "
            "from the parameters it records"
        )
    if twin.family.startswith("cam_") and twin.parameter("profile") != "disc":
        raise NoClosedForm("closed forms exist for the eccentric disc profile only")
    grid = np.asarray(scenario.times() if times is None else times, dtype=float)
    return FAMILIES[twin.family](twin, grid)  # the twin carries the family's parameters
