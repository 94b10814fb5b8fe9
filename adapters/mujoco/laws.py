"""Gears, racks and drivers as linear laws in MuJoCo's joint coordinates (no MuJoCo here).

Each law is an affine form in qpos that must vanish. A driver's time function is carried by a
"clock" joint of its own: a free rotor started at the driver's rate gives f(t) = start + rate t
exactly, a rotor on a spring of stiffness armature * omega^2 gives a harmonic f(t). The clock has a
huge armature, so the constraint force it feels does not disturb it, and MuJoCo's equality then ties
two moving joints together: its stabilising damping acts on their relative speed, which is zero.
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
from scenarios.motions import Constant, ConstantSpeed, Harmonic, Motion
from scenarios.scenario import Scenario


@dataclass(frozen=True)
class Clock:
    """A clock joint whose free motion is c(t): c(0) = q0, c'(0) = v0, c'' = -omega2 c."""

    joint: str
    q0: float
    v0: float
    omega2: float

    def at(self, t: float) -> tuple[float, float]:
        """The clock's exact (qpos, qvel) at time t."""
        if self.omega2 == 0.0:
            return self.q0 + self.v0 * t, self.v0
        w = math.sqrt(self.omega2)
        c, s = math.cos(w * t), math.sin(w * t)
        return self.q0 * c + self.v0 / w * s, -self.q0 * w * s + self.v0 * c


@dataclass(frozen=True)
class Law:
    """`form` (over tree joints and maybe the clock's joint) = 0."""

    name: str
    form: Affine
    clock: Clock | None = None

    def terms(self) -> list[tuple[str, float]]:
        """Joints with a non-negligible coefficient, tree joints before the clock."""
        scale = max((abs(c) for c in self.form.coefs.values()), default=0.0)
        terms = [(j, c) for j, c in self.form.coefs.items() if abs(c) > 1e-14 * scale]
        clock = self.clock.joint if self.clock else ""
        return sorted(terms, key=lambda t: t[0] == clock)


def laws(scenario: Scenario, tree: Tree) -> list[Law]:
    """Every gear, rack and driver of the scenario as a law; TreeError where one is not linear in
    this tree or is of a kind MuJoCo has no equality for."""
    found = []
    for joint in scenario.joints:
        if isinstance(joint, GearPair):
            found.append(Law(joint.name, _gear(tree, joint)))
        elif isinstance(joint, RackPinion):
            found.append(Law(joint.name, _rack(tree, joint)))
        elif not isinstance(joint, Ground | Revolute | Prismatic | KnifeEdgeCam | RollerCam | FlatFaceCam):
            raise TreeError(f"MuJoCo has no equality for a {type(joint).__name__} ('{joint.name}')")
    found.extend(_driver(tree, d) for d in scenario.drivers)
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


def _driver(tree: Tree, d: Driver) -> Law:
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
    offset, clock = _clock(f"clock_{d.name}", d.motion)
    form = value + Affine(-offset, {})
    if clock is not None:
        form = form + Affine(0.0, {clock.joint: -1.0})
    return Law(d.name, form, clock)


def _clock(name: str, motion: Motion) -> tuple[float, Clock | None]:
    """f(t) = offset + c(t), with c the clock's motion (None for a constant)."""
    if isinstance(motion, ConstantSpeed):
        return motion.start, Clock(name, 0.0, motion.rate, 0.0)
    if isinstance(motion, Harmonic):
        a, w, p = motion.amplitude, motion.omega, motion.phase
        return motion.mean, Clock(name, a * math.cos(p), -a * w * math.sin(p), w * w)
    if isinstance(motion, Constant):
        return motion.value, None
    raise TreeError(f"MuJoCo cannot drive a {type(motion).__name__} motion")
