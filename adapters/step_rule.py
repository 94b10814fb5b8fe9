"""The one rule every fixed-step integrator's default step follows: a fixed number of steps per
shortest period of the scenario's motion, never a function of the output grid.

The shortest period is the smallest of
- each driver motion's period (constant speed: one turn, 2 pi / |rate|; harmonic: 2 pi / |omega|;
  a tabulated law: its shortest knot interval; a polynomial sum ck t^k: the shortest time any of
  its terms alone takes to advance by 2 pi, (2 pi / |ck|)^(1/k), which for k = 1 is constant
  speed's turn and needs no horizon);
- in free dynamics (where forces move the bodies):
  - each load's period (a harmonic torque or force);
  - each spring's mode, 2 pi sqrt(m / k), with m the lightest body it holds (the inertia for a
    rotational spring), and each damper's time 2 pi m / c;
  - the stiffest gravity mode of a hanging chain of N bodies, 2 pi / (2 sqrt(N g / l)), l the
    shortest link (the characteristic length where no body has a length);
  - each body's start rate, 2 pi / |omega| and 2 pi L / |v|, L the characteristic length;
- 1 s when nothing above sets a time.
An engine's default step is this period divided by its steps-per-period constant (declared in its
own subpackage): `rule_step(scenario, steps_per_period)`. MuJoCo's constraint mode is set by its
time constant, itself a fixed number of the rule's steps (adapters.mujoco.settings).
The output grid (t_end, steps) is deliberately not an input: it changes where outputs are written,
not the rule's step (adapters.lattice; an engine that cannot side-step to an output shortens its
step to put an even grid's outputs on its steps, adapters.lattice.outputs_on_steps).
"""

from __future__ import annotations

import math
from collections.abc import Iterator

from adapters.base import Setting
from scenarios.bodies import GROUND
from scenarios.drivers import PointPathDriver, RelativeDisplacementDriver
from scenarios.forces import AppliedForce, AppliedTorque, RotationalSpringDamper, SpringDamper
from scenarios.motion_laws import Polynomial, TabulatedLaw
from scenarios.motions import ConstantSpeed, Harmonic, Motion
from scenarios.scenario import Scenario

FALLBACK_PERIOD = 1.0
"""Seconds: the period of a scenario in which nothing sets a time (no driver, load, spring,
gravity or start rate)."""
RULE = (
    "default step = (shortest period of the motion) / (the engine's steps per period); the shortest "
    "period is the least of the drivers' and loads' periods and, in free dynamics, the springs' "
    "2 pi sqrt(m/k), the dampers' 2 pi m/c, the gravity chain's 2 pi / (2 sqrt(N g / l)) and the "
    "start rates' 2 pi/|omega|; the output grid does not set the step (outputs off the step lattice "
    "are reached by a side step from the lattice; an engine that cannot side-step shortens its step "
    "to put an even grid's outputs on its steps, and interpolates an uneven grid's)"
)
"""The rule in one sentence, as `mbxval list` prints it."""


def shortest_period(scenario: Scenario) -> float:
    """The shortest period of the scenario's motion, in seconds (see the module docstring)."""
    found = [p for p in _periods(scenario) if math.isfinite(p) and p > 0.0]
    return min(found) if found else FALLBACK_PERIOD


def rule_step(scenario: Scenario, steps_per_period: float) -> float:
    """The default step of an engine taking `steps_per_period` steps per shortest period."""
    return shortest_period(scenario) / steps_per_period


def at_step(setting: Setting, dt: float) -> Setting:
    """`setting` moved to the step `dt`, its time constant (`tc`, seconds) kept the same number of
    steps: the rule ties both to the step."""
    if setting.get("tc") is None or setting.get("dt") is None:
        return setting.replace(dt=dt)
    return setting.replace(dt=dt, tc=float(setting["tc"]) * dt / float(setting["dt"]))


def _periods(scenario: Scenario) -> Iterator[float]:
    for driver in scenario.drivers:
        if isinstance(driver, PointPathDriver | RelativeDisplacementDriver):
            yield from map(_motion_period, (driver.motion_x, driver.motion_y))
        else:
            yield _motion_period(driver.motion)
    if scenario.analysis != "dynamic":
        return  # a kinematically driven mechanism moves as its drivers say, whatever its forces
    yield from _force_periods(scenario)
    yield _gravity_period(scenario)
    for body in scenario.bodies:
        vx, vy, omega = body.rate
        yield _turn(omega)
        yield _turn(math.hypot(vx, vy) / scenario.characteristic_length)


def _force_periods(scenario: Scenario) -> Iterator[float]:
    masses = {b.name: (b.mass, b.inertia) for b in scenario.bodies}
    for force in scenario.forces:
        if isinstance(force, AppliedTorque):
            yield _motion_period(force.torque)
        elif isinstance(force, AppliedForce):
            yield from map(_motion_period, (force.fx, force.fy))
        elif isinstance(force, SpringDamper | RotationalSpringDamper):
            held = (
                (force.p_i.body, force.p_j.body)
                if isinstance(force, SpringDamper)
                else (force.body_i, force.body_j)
            )
            which = 0 if isinstance(force, SpringDamper) else 1
            lightest = min((masses[b][which] for b in held if b != GROUND), default=math.inf)
            if force.stiffness > 0.0:
                yield 2.0 * math.pi * math.sqrt(lightest / force.stiffness)
            if force.damping > 0.0:
                yield 2.0 * math.pi * lightest / force.damping


def _gravity_period(scenario: Scenario) -> float:
    g = math.hypot(*scenario.gravity)
    if g <= 0.0 or not scenario.bodies:
        return math.inf
    lengths = [b.length for b in scenario.bodies if b.length > 0.0]
    shortest = min(lengths) if lengths else scenario.characteristic_length
    return 2.0 * math.pi / (2.0 * math.sqrt(len(scenario.bodies) * g / shortest))


def _motion_period(motion: Motion) -> float:
    if isinstance(motion, ConstantSpeed):
        return _turn(motion.rate)
    if isinstance(motion, Harmonic):
        return _turn(motion.omega)
    if isinstance(motion, TabulatedLaw) and len(motion.times) > 1:
        return min(b - a for a, b in zip(motion.times, motion.times[1:], strict=False))
    if isinstance(motion, Polynomial):
        terms = [(k, abs(c)) for k, c in enumerate(motion.coefficients) if k and c]
        return min(((2.0 * math.pi / c) ** (1.0 / k) for k, c in terms), default=math.inf)
    return math.inf


def _turn(rate: float) -> float:
    return 2.0 * math.pi / abs(rate) if rate else math.inf
