"""The closed form of every example file, by file name: each body's (position, velocity,
acceleration) arrays of shape (len(t), 3), derived independently of every engine (tests/examples/
dyads.py for the linkages; the Whitworth's and the oscillators' in their own test modules; the
slider-crank's is the family's, scenarios.closed_form; the polynomial slider-crank's by hand below;
the spline cam's on its pitch curve, tests/support/examples/spline_cam.py)."""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

import scenarios
from scenarios.closed_form import exact
from tests.support.examples.dyads import Angle, Motion2, direction, dyad, fixed, frame, on_body
from tests.support.examples.spline_cam import cam_roller_spline

Expected = dict[str, tuple[np.ndarray, np.ndarray, np.ndarray]]


def constant_speed(times: np.ndarray, start: float, rate: float) -> Angle:
    return Angle(start + rate * times, np.full_like(times, rate), np.zeros_like(times))


def harmonic(times: np.ndarray, mean: float, amplitude: float, omega: float) -> Angle:
    c, s = np.cos(omega * times), np.sin(omega * times)
    return Angle(mean + amplitude * c, -amplitude * omega * s, -amplitude * omega**2 * c)


def watt_six_bar(t: np.ndarray) -> Expected:
    o2, o4, o6 = fixed((0.0, 0.0), t.size), fixed((0.3, 0.0), t.size), fixed((0.45, -0.3), t.size)
    crank = constant_speed(t, 0.0, 10.0)
    a = on_body(o2, crank, (0.1, 0.0))
    b = dyad(a, o4, 0.3, 0.25, 1.0)
    ternary = direction(o4, b)
    c = on_body(o4, ternary, (-0.15, 0.0))
    d = dyad(c, o6, 0.25, 0.2, 1.0)
    return {
        "crank": frame(o2, crank),
        "coupler": frame(a, direction(a, b)),
        "ternary": frame(o4, ternary),
        "link5": frame(c, direction(c, d)),
        "output": frame(o6, direction(o6, d)),
    }


def watt_linkage(t: np.ndarray, swing: float = 0.3) -> tuple[Angle, Motion2, Motion2, Motion2]:
    """Watt's linkage: the left rocker's angle, its pin A, the right rocker's pin B, its pivot."""
    o2, o4 = fixed((0.0, 0.0), t.size), fixed((0.4, 0.1), t.size)
    left = harmonic(t, 0.0, swing, 2.0 * np.pi)
    a = on_body(o2, left, (0.2, 0.0))
    b = dyad(a, o4, 0.1, 0.2, 1.0)
    return left, a, b, o4


def watt_straight_line(t: np.ndarray) -> Expected:
    left, a, b, o4 = watt_linkage(t)
    coupler = direction(a, b)
    midpoint = on_body(a, coupler, (0.05, 0.0))
    return {
        "rocker_left": frame(fixed((0.0, 0.0), t.size), left),
        "coupler": frame(midpoint, coupler),
        "rocker_right": frame(o4, direction(o4, b)),
    }


def peaucellier_lipkin(t: np.ndarray) -> Expected:
    origin, pivot = fixed((0.0, 0.0), t.size), fixed((0.12, 0.0), t.size)
    crank = constant_speed(t, -1.0, 1.0)
    a = on_body(pivot, crank, (0.12, 0.0))
    b, d = dyad(origin, a, 0.3, 0.15, 1.0), dyad(origin, a, 0.3, 0.15, -1.0)
    p = dyad(b, d, 0.15, 0.15, 1.0)
    return {
        "crank": frame(pivot, crank),
        "ob": frame(origin, direction(origin, b)),
        "od": frame(origin, direction(origin, d)),
        "ab": frame(a, direction(a, b)),
        "ad": frame(a, direction(a, d)),
        "bp": frame(p, direction(p, b)),
        "dp": frame(p, direction(p, d)),
    }


def crank_rocker_from_rocker(t: np.ndarray) -> Expected:
    o2, o4 = fixed((0.0, 0.0), t.size), fixed((0.3, 0.0), t.size)
    rocker = harmonic(t, 1.97, 0.35, 2.0)
    b = on_body(o4, rocker, (0.25, 0.0))
    a = dyad(o2, b, 0.1, 0.3, -1.0)
    return {
        "crank": frame(o2, direction(o2, a)),
        "coupler": frame(a, direction(a, b)),
        "rocker": frame(o4, rocker),
    }


def slider_crank(t: np.ndarray) -> Expected:
    truth = exact(scenarios.build("slider_crank"), t)
    levels = (truth.position, truth.velocity, truth.acceleration)
    return {body: tuple(lv[:, k, :] for lv in levels) for k, body in enumerate(truth.bodies)}  # type: ignore[index,misc]


# The slider-crank under a quartic crank law (examples/slider_crank_polynomial.toml).
QUARTIC = (0.3, 50.0, 200.0, -1000.0, 5000.0)
CRANK, ROD = 0.2, 0.4


def slider_crank_polynomial(t: np.ndarray) -> Expected:
    """Crank pin A from the crank angle; the slider B on y = 0 to the right of A, B_x = A_x + h with
    h = sqrt(l^2 - A_y^2), h' = -A_y A_y' / h, h'' = -(A_y'^2 + A_y A_y'' + h'^2) / h."""
    law = np.polynomial.Polynomial(QUARTIC)
    crank = Angle(law(t), law.deriv()(t), law.deriv(2)(t))
    origin = fixed((0.0, 0.0), t.size)
    a = on_body(origin, crank, (CRANK, 0.0))
    y, dy, ddy = a.p[:, 1], a.v[:, 1], a.a[:, 1]
    h = np.sqrt(ROD**2 - y**2)
    dh = -y * dy / h
    ddh = -(dy**2 + y * ddy + dh**2) / h
    zero = np.zeros_like(t)
    b = Motion2(
        np.column_stack([a.p[:, 0] + h, zero]),
        np.column_stack([a.v[:, 0] + dh, zero]),
        np.column_stack([a.a[:, 0] + ddh, zero]),
    )
    rod = direction(a, b)
    return {
        "crank": frame(on_body(origin, crank, (CRANK / 2, 0.0)), crank),
        "rod": frame(on_body(a, rod, (ROD / 2, 0.0)), rod),
        "slider": frame(b, Angle(zero, zero, zero)),
    }


# The Whitworth quick-return (derivation: tests/examples/test_whitworth.py).
R, D, OMEGA = 0.1, 0.05, 10.0


def whitworth(t: np.ndarray) -> dict[str, tuple[np.ndarray, np.ndarray, np.ndarray]]:
    theta2 = OMEGA * t
    c2, s2 = np.cos(theta2), np.sin(theta2)
    a = np.column_stack([R * c2, D + R * s2])  # O4 at the origin
    da = np.column_stack([-R * OMEGA * s2, R * OMEGA * c2])
    dda = np.column_stack([-R * OMEGA**2 * c2, -R * OMEGA**2 * s2])
    s = np.hypot(a[:, 0], a[:, 1])
    theta4 = np.unwrap(np.arctan2(a[:, 1], a[:, 0]))
    e_r = np.column_stack([np.cos(theta4), np.sin(theta4)])
    e_t = np.column_stack([-e_r[:, 1], e_r[:, 0]])
    ds = np.einsum("ij,ij->i", da, e_r)
    omega4 = np.einsum("ij,ij->i", da, e_t) / s
    coriolis = 2.0 * ds * omega4
    alpha4 = (np.einsum("ij,ij->i", dda, e_t) - coriolis) / s
    n = t.size
    zeros, full = np.zeros(n), np.full(n, OMEGA)
    pivot = np.column_stack([zeros, np.full(n, D)])
    return {
        "crank": (np.column_stack([pivot, theta2]), np.column_stack([zeros, zeros, full]), np.zeros((n, 3))),
        "block": (
            np.column_stack([a, theta4]),
            np.column_stack([da, omega4]),
            np.column_stack([dda, alpha4]),
        ),
        "slotted_link": (
            np.column_stack([zeros, zeros, theta4]),
            np.column_stack([zeros, zeros, omega4]),
            np.column_stack([zeros, zeros, alpha4]),
        ),
    }


# Two damped linear oscillators (derivation: tests/examples/test_damped_oscillators.py).
BLOCK = {"mass": 2.5, "stiffness": 250.0, "damping": 5.0, "rest": 0.3 + 2.5 / 250.0, "start": 0.4}
DISC = {"mass": 0.01, "stiffness": 1.0, "damping": 0.02, "rest": 0.1 / 1.0, "start": 0.5}


def oscillator(t: np.ndarray, p: dict[str, float]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(value, rate, acceleration) of a damped oscillator released from rest at p["start"]."""
    wn2, s = p["stiffness"] / p["mass"], p["damping"] / (2.0 * p["mass"])
    wd, u0 = math.sqrt(wn2 - s * s), p["start"] - p["rest"]
    decay = np.exp(-s * t)
    u = decay * (u0 * np.cos(wd * t) + s * u0 / wd * np.sin(wd * t))
    du = -decay * wn2 / wd * u0 * np.sin(wd * t)
    return p["rest"] + u, du, -wn2 * u - 2.0 * s * du


def damped_oscillators(t: np.ndarray) -> dict[str, tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """Each body's (position, velocity, acceleration) arrays of shape (len(t), 3)."""
    x, zero = oscillator(t, BLOCK), np.zeros_like(t)
    theta = oscillator(t, DISC)
    block = tuple(np.column_stack([x[k], zero, zero]) for k in range(3))
    disc = tuple(np.column_stack([x[k], zero, theta[k]]) for k in range(3))
    return {"block": block, "disc": disc}  # type: ignore[dict-item]


CLOSED_FORMS: dict[str, Callable[[np.ndarray], Expected]] = {
    "whitworth_quick_return": whitworth,
    "watt_six_bar": watt_six_bar,
    "watt_straight_line": watt_straight_line,
    "peaucellier_lipkin": peaucellier_lipkin,
    "crank_rocker_from_rocker": crank_rocker_from_rocker,
    "slider_crank": slider_crank,
    "slider_crank_polynomial": slider_crank_polynomial,
    "damped_oscillators": damped_oscillators,
    "cam_roller_spline": cam_roller_spline,
}
"""Every example file's closed form, by its file name."""
