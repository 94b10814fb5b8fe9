"""Pinocchio's settings by the one rule (adapters.step_rule): its dynamic modes step a fixed number
of steps per shortest period of the motion, whatever the output grid, and their Baumgarte gains
are critically damped with a time constant of one radian of that period.

The ladder runs each dynamic mode over rungs of steps per period (PER_PERIOD) and the Baumgarte
gains at the default step scaled by GAIN_FACTORS; a rung whose run would take more than
STEP_BUDGET steps over the horizon is left out (the first rung always stays): past it the error
sits on the mode's floor or the run costs minutes of Python for nothing new.
"""

from __future__ import annotations

import math

from adapters.base import Setting
from adapters.probes import MASS, STIFFNESS, Probe
from adapters.step_rule import rule_step, shortest_period
from scenarios.scenario import Scenario

KINEMATIC, DYNAMIC, BAUMGARTE, EULER = "kinematic", "dynamic", "baumgarte", "euler"
STEPS_PER_PERIOD = {DYNAMIC: 1000, BAUMGARTE: 1000, EULER: 10000}
"""Pinocchio's constant of the rule, per mode: RK4 (dynamic, baumgarte) and semi-implicit Euler."""
PER_PERIOD = {
    DYNAMIC: (100, 300, 1000, 3000, 10000),
    BAUMGARTE: (100, 300, 1000, 3000, 10000),
    EULER: (1000, 3000, 10000, 30000),
}
"""Steps per shortest period in the ladder, per mode."""
GAIN_FACTORS = (0.25, 4.0)
"""Baumgarte's rate w (kp = w^2, kd = 2 w) times these, swept at the default step."""
STEP_BUDGET = 3.0e4
"""Steps over the horizon above which a ladder rung is left out (a step of more than 8 bodies
counts as bodies / 8 steps)."""


def gains(scenario: Scenario, mode: str, factor: float = 1.0) -> tuple[float, float]:
    """Baumgarte gains (kp, kd): none in the dynamic mode, else critically damped at
    w = factor * 2 pi / shortest period."""
    if mode not in (BAUMGARTE, EULER):
        return 0.0, 0.0
    w = factor * 2.0 * math.pi / shortest_period(scenario)
    return w * w, 2.0 * w


def rule_setting(scenario: Scenario, mode: str, steps_per_period: float | None = None) -> Setting:
    """`mode` at `steps_per_period` steps per shortest period (default: the mode's constant)."""
    kp, kd = gains(scenario, mode)
    per_period = STEPS_PER_PERIOD[mode] if steps_per_period is None else steps_per_period
    return Setting.of(mode, dt=rule_step(scenario, per_period), kp=kp, kd=kd)


def dynamic_ladder(scenario: Scenario) -> list[Setting]:
    """Each dynamic mode over its ladder within the budget, then the gains at the default step."""
    weight = max(1.0, len(scenario.bodies) / 8)
    settings = [
        rule_setting(scenario, mode, n)
        for mode, ladder in PER_PERIOD.items()
        for n in ladder
        if n == ladder[0] or scenario.t_end / rule_step(scenario, n) * weight <= STEP_BUDGET
    ]
    for factor in GAIN_FACTORS:
        kp, kd = gains(scenario, BAUMGARTE, factor)
        settings.append(rule_setting(scenario, BAUMGARTE).replace(kp=kp, kd=kd))
    return settings


STRESS_STEPS_PER_TURN = (100, 300, 1000)
"""The stiffness probe's RK4 steps per crank revolution."""
STRESS_GAINS = (1.0, 1e2, 1e3, 1e4)
"""The stiffness probe's Baumgarte rates, in crank speeds (kp = (g w)^2, kd = 2 g w)."""
MASS_STEPS_PER_TURN = 1000
"""The mass probe's RK4 steps per crank revolution."""


def probe_settings(probe: Probe, scenario: Scenario, default: Setting) -> list[Setting] | None:
    """Pinocchio's settings for a stress case (adapters.probes), its `default` first. Stiffness:
    Baumgarte gains against RK4 steps per crank revolution. Mass: the dynamic mode (RK4, no gains)
    beside the kinematic default, the result depending on the masses."""
    w = abs(float(scenario.parameter("omega")))
    turn = 2 * math.pi / w
    if probe == STIFFNESS:
        stabilised = [
            Setting.of(BAUMGARTE, dt=turn / n, kp=(g * w) ** 2, kd=2 * g * w)
            for n in STRESS_STEPS_PER_TURN
            for g in STRESS_GAINS
        ]
        return [default, *stabilised]
    if probe == MASS:
        return [default, Setting.of(DYNAMIC, dt=turn / MASS_STEPS_PER_TURN, kp=0.0, kd=0.0)]
    return None
