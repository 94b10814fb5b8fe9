"""A chain of N four-bar loops sharing links, after the IFToMM N-four-bar benchmark: ground pivots
O_k = (k g, 0), k = 0..N, each carrying a rocker of length L; coupler k joins the tips of rockers
k - 1 and k. Rocker 0 is the crank, driven to swing theta(t) = theta0 + amplitude sin(omega t).

Every loop is a parallelogram (couplers as long as the pivot spacing), so every rocker turns with
the crank and every coupler stays horizontal: rocker k's tip is O_k + L (cos theta, sin theta).
A parallelogram is a change-point linkage: C_q is singular where rockers and couplers line up
(theta = 0 or pi), where the chain could fold into an anti-parallelogram. The default swing keeps
theta within (0, pi). A swing that turns back exactly there is reported as a singular
configuration; one that swings through between grid points may go unnoticed (C_q's determinant does
not change sign there), the predictor carrying the solution across on the parallelogram branch.
"""

from __future__ import annotations

import math

import numpy as np

from scenarios.bodies import GROUND, Body, Point
from scenarios.drivers import AbsoluteDriver
from scenarios.families.four_bar import link
from scenarios.family import (
    MAX_ANGLE,
    MAX_GRID_STEPS,
    MAX_RATE,
    MAX_REVOLUTIONS,
    Family,
    Parameter,
    angle,
    count,
    length,
    positive,
)
from scenarios.joints import Revolute
from scenarios.motions import Harmonic
from scenarios.scenario import (
    ParameterValue,
    Scenario,
)
from scenarios.trajectory import Trajectory


def rocker(k: int) -> str:
    """The name of rocker k (rocker 0 is the crank)."""
    return "crank" if k == 0 else f"rocker_{k}"


def _build(p: dict[str, ParameterValue], variant: str) -> Scenario:
    loops, length, spacing = int(p["loops"]), float(p["link_length"]), float(p["coupler_length"])
    omega, amplitude, theta0 = float(p["omega"]), float(p["amplitude"]), float(p["theta0"])

    def tip(k: int) -> tuple[float, float]:
        return k * spacing + length * math.cos(theta0), length * math.sin(theta0)

    bodies: list[Body] = [link("crank", (0.0, 0.0), tip(0), length)]
    joints: list[Revolute] = [Revolute("O0", Point(GROUND, (0.0, 0.0)), Point("crank", (-length / 2, 0.0)))]
    for k in range(1, loops + 1):
        coupler = f"coupler_{k}"
        bodies += [
            link(coupler, tip(k - 1), tip(k), spacing),
            link(rocker(k), (k * spacing, 0.0), tip(k), length),
        ]
        joints += [
            Revolute(f"A{k}", Point(rocker(k - 1), (length / 2, 0.0)), Point(coupler, (-spacing / 2, 0.0))),
            Revolute(f"B{k}", Point(coupler, (spacing / 2, 0.0)), Point(rocker(k), (length / 2, 0.0))),
            Revolute(f"O{k}", Point(GROUND, (k * spacing, 0.0)), Point(rocker(k), (-length / 2, 0.0))),
        ]
    # theta0 + amplitude sin(omega t), written as Harmonic's mean + amplitude cos(omega t + phase).
    swing = Harmonic(theta0, amplitude, omega, phase=-math.pi / 2)
    return Scenario(
        family="four_bar_chain",
        variant=variant,
        bodies=tuple(bodies),
        joints=tuple(joints),
        drivers=(AbsoluteDriver("crank_drive", "crank", "theta", swing),),
        t_end=float(p["periods"]) * 2.0 * math.pi / omega,
        steps=int(p["steps"]),
        characteristic_length=length,
        parameters=tuple(p.items()),
        description=f"chain of {loops} parallelogram four-bar loops sharing rockers, crank swinging",
    )


def closed_form(scenario: Scenario, t: np.ndarray) -> Trajectory:
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


FAMILY = Family(
    name="four_bar_chain",
    summary="N parallelogram four-bar loops in a row sharing rockers (IFToMM N-four-bar), crank swinging",
    parameters={
        "loops": count(4, 1, 1000),
        "link_length": length(0.1),
        "coupler_length": length(0.1),
        "omega": positive(10.0, MAX_RATE, "rad/s"),
        "amplitude": Parameter(1.0, "rad", low=-MAX_ANGLE, high=MAX_ANGLE),
        "theta0": angle(math.pi / 2),
        "periods": positive(1.0, MAX_REVOLUTIONS, "periods"),
        "steps": count(200, 1, MAX_GRID_STEPS),
    },
    build=_build,
    closed_form=closed_form,
    variants={},
)
