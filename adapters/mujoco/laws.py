"""Gears, racks and drivers as laws in MuJoCo's joint coordinates (no MuJoCo here).

Each law is an affine form in qpos that must vanish (a polynomial drive: a quartic in its clock).
A driver's time function is carried by a "clock" joint of its own: a free rotor started at the
driver's rate gives f(t) = start + rate t exactly, a rotor on a spring of stiffness
armature * omega^2 gives a harmonic f(t), a free rotor at unit rate (c = t) tied through MuJoCo's
quartic `polycoef` gives a polynomial of degree <= 4. Any other law (a tabulated spline, a
polynomial of higher degree) is a "steered" clock: a free rotor started at f(0), f'(0) and driven
by a motor whose control is its inertia times f''(t) at every integrator stage (adapters.mujoco.
controls). The clock has a huge armature, so the constraint force it feels does not disturb it,
and MuJoCo's equality then ties two moving joints together: its stabilising damping acts on their
relative speed, which is zero.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from adapters.mujoco.tree import Affine, Tree, TreeError, angle, position, rot
from scenarios.bodies import Point
from scenarios.cams import FlatFaceCam, KnifeEdgeCam, RollerCam
from scenarios.drivers import AbsoluteDriver, Driver, RelativeRotationDriver
from scenarios.gears import GearPair, RackPinion
from scenarios.joints import Ground, Prismatic, Revolute
from scenarios.motion_laws import Polynomial
from scenarios.motions import Constant, ConstantSpeed, Harmonic, Motion
from scenarios.scenario import Scenario

QUARTIC = 4
"""The highest power of MuJoCo's joint and tendon equality (polycoef a0 ... a4)."""


@dataclass(frozen=True)
class Clock:
    """A clock joint whose free motion is c(t): c(0) = q0, c'(0) = v0, c'' = -omega2 c; or, with
    `law` set, steered by its motor so that c(t) = law.f(t)."""

    joint: str
    q0: float
    v0: float
    omega2: float
    law: Motion | None = None

    def at(self, t: float) -> tuple[float, float]:
        """The clock's exact (qpos, qvel) at time t."""
        if self.law is not None:
            return self.law.f(t), self.law.df(t)
        if self.omega2 == 0.0:
            return self.q0 + self.v0 * t, self.v0
        w = math.sqrt(self.omega2)
        c, s = math.cos(w * t), math.sin(w * t)
        return self.q0 * c + self.v0 / w * s, -self.q0 * w * s + self.v0 * c

    def acc(self, t: float) -> float:
        """The clock's exact acceleration at time t."""
        if self.law is not None:
            return self.law.ddf(t)
        return -self.omega2 * self.at(t)[0]


@dataclass(frozen=True)
class Law:
    """`form` (over tree joints and maybe the clock's joint) = 0, where the clock's term k c stands
    for k (p1 c + p2 c^2 + ...) with `powers` = (p1, p2, ...): linear by default."""

    name: str
    form: Affine
    clock: Clock | None = None
    powers: tuple[float, ...] = (1.0,)

    @property
    def linear(self) -> bool:
        return self.powers == (1.0,)

    def linearised(self) -> Law:
        """The same law with its clock entering linearly (equal to it at c = 0, where the clock of a
        polynomial starts): the driven coordinate then moves at the clock's rate."""
        return Law(self.name, self.form, self.clock)

    def terms(self) -> list[tuple[str, float]]:
        """Joints with a non-negligible coefficient, tree joints before the clock."""
        scale = max((abs(c) for c in self.form.coefs.values()), default=0.0)
        terms = [(j, c) for j, c in self.form.coefs.items() if abs(c) > 1e-14 * scale]
        clock = self.clock.joint if self.clock else ""
        return sorted(terms, key=lambda t: t[0] == clock)


def laws(scenario: Scenario, tree: Tree, steer: bool = False) -> list[Law]:
    """Every gear, rack and driver of the scenario as a law; TreeError where one is not linear in
    this tree or is of a kind MuJoCo has no equality for. `steer`: polynomials of degree 2 to 4 by
    steered clocks too, rather than through polycoef."""
    found = []
    for joint in scenario.joints:
        if isinstance(joint, GearPair):
            found.append(Law(joint.name, _gear(tree, joint)))
        elif isinstance(joint, RackPinion):
            found.append(Law(joint.name, _rack(tree, joint)))
        elif not isinstance(joint, Ground | Revolute | Prismatic | KnifeEdgeCam | RollerCam | FlatFaceCam):
            raise TreeError(f"MuJoCo has no equality for a {type(joint).__name__} ('{joint.name}')")
    found.extend(_driver(tree, d, steer) for d in scenario.drivers)
    for law in found:
        if not law.terms():
            raise TreeError(f"'{law.name}' involves no moving joint")
    return found


def _gear(tree: Tree, g: GearPair) -> Affine:
    sign = -1.0 if g.internal else 1.0
    ri, rj = g.radius_i, sign * g.radius_j
    form = (angle(tree, g.gear_i) + Affine(-g.theta0_i, {})).scaled(ri)
    form = form + (angle(tree, g.gear_j) + Affine(-g.theta0_j, {})).scaled(rj)
    return form + (angle(tree, g.carrier) + Affine(-g.theta0_carrier, {})).scaled(-(ri + rj))


def _rack(tree: Tree, r: RackPinion) -> Affine:
    rack_angle = angle(tree, r.rack.body)
    pitch, centre = position(tree, r.rack), position(tree, r.centre)
    if rack_angle.coefs or pitch is None or centre is None:
        raise TreeError(f"rack and pinion '{r.name}' is not linear in this tree (the rack turns)")
    u = rot(rack_angle.const) @ np.array(r.axis, dtype=float)
    u /= np.linalg.norm(u)
    along = (pitch[0] + centre[0].scaled(-1.0)).scaled(u[0]) + (pitch[1] + centre[1].scaled(-1.0)).scaled(
        u[1]
    )
    turn = angle(tree, r.centre.body) + rack_angle.scaled(-1.0)
    return along + turn.scaled(-r.radius) + Affine(-r.offset, {})


def _driver(tree: Tree, d: Driver, steer: bool) -> Law:
    if isinstance(d, AbsoluteDriver):
        if d.coordinate == "theta":
            value = angle(tree, d.body)
        else:
            xy = position(tree, Point(d.body))
            if xy is None:
                raise TreeError(f"driver '{d.name}': {d.body}.{d.coordinate} is not linear in this tree")
            value = xy[0] if d.coordinate == "x" else xy[1]
    elif isinstance(d, RelativeRotationDriver):
        value = angle(tree, d.body_i) + angle(tree, d.body_j).scaled(-1.0)
    else:
        raise TreeError(f"MuJoCo has no equality for a {type(d).__name__} ('{d.name}')")
    offset, clock, powers = _clock(f"clock_{d.name}", d.motion, steer)
    form = value + Affine(-offset, {})
    if clock is not None:
        form = form + Affine(0.0, {clock.joint: -1.0})
        if powers != (1.0,) and not value.coefs:
            raise TreeError(f"driver '{d.name}' involves no moving joint")
    return Law(d.name, form, clock, powers)


def _clock(name: str, motion: Motion, steer: bool) -> tuple[float, Clock | None, tuple[float, ...]]:
    """f(t) = offset + p1 c(t) + p2 c(t)^2 + ..., with c the clock's motion (None for a constant)
    and (p1, p2, ...) the powers: (1,) but for a polynomial of degree 2 to 4 (unless `steer`)."""
    if isinstance(motion, ConstantSpeed):
        return motion.start, Clock(name, 0.0, motion.rate, 0.0), (1.0,)
    if isinstance(motion, Harmonic):
        a, w, p = motion.amplitude, motion.omega, motion.phase
        return motion.mean, Clock(name, a * math.cos(p), -a * w * math.sin(p), w * w), (1.0,)
    if isinstance(motion, Constant):
        return motion.value, None, (1.0,)
    if isinstance(motion, Polynomial):
        coefficients = list(motion.coefficients)
        while len(coefficients) > 1 and coefficients[-1] == 0.0:
            coefficients.pop()
        if len(coefficients) == 1:
            return coefficients[0], None, (1.0,)
        if len(coefficients) == 2:
            return coefficients[0], Clock(name, 0.0, coefficients[1], 0.0), (1.0,)
        if len(coefficients) - 1 <= QUARTIC and not steer:
            return coefficients[0], Clock(name, 0.0, 1.0, 0.0), tuple(coefficients[1:])
    return 0.0, Clock(name, motion.f(0.0), motion.df(0.0), 0.0, law=motion), (1.0,)
