"""MuJoCo's settings by the one rule (adapters.step_rule): the step is a fixed number of steps per
shortest period of the motion, the equalities' time constant `tc` (seconds) a fixed number of those
steps, for every scenario whatever its size and its output grid.

The time constant sets MuJoCo's constraint mode: a violation relaxes over tc, so RK4 sees the mode
at tc / dt steps. At 2 steps (MuJoCo's floor) RK4 under-resolves it and the accelerations carry the
ringing (slider-crank 4.0e-3); TC_STEPS resolves it at the same cost. Softness ((1 - d) tc^2) grows
with tc, so positions lose a little of what accelerations gain.

The ladder (one work-precision curve per integrator): each integrator over rungs of steps per
period; RK4's time constant over TC_LADDER steps at the default step and at a tenth of it; the
impedance (solimp) at the default. A rung whose run takes more than STEP_BUDGET steps over the
horizon (weighted by bodies / 8 above 8 bodies) is left out, the coarsest always kept: the suite's
time goes to points that show something new. Euler at coarse steps is such a rung, swept, never a
silent default for large systems.
"""

from __future__ import annotations

from adapters.base import Setting
from adapters.probes import MASS, STIFFNESS, Probe
from adapters.step_rule import at_step, rule_step
from scenarios.scenario import Scenario

STEPS_PER_PERIOD = 2000
"""MuJoCo's constant of the rule (at 1000 the soft closures' positions are twice as far off, the
cam contacts' penetration four times)."""
TC_STEPS = 4.0
"""The equalities' time constant in rule steps."""
IMPEDANCE = 0.9999
"""solimp of the equalities: MuJoCo's stiffest."""
LADDERS = {
    "RK4": (200, 600, 2000, 6000, 20000),
    "implicitfast": (600, 2000, 6000, 20000),
    "implicit": (600, 2000, 6000, 20000),
    "Euler": (60, 200, 600, 2000, 6000, 20000),
}
"""Steps per shortest period in the ladder, per integrator."""
KINEMATIC_MODES = ("RK4", "implicitfast")
"""The integrators swept on driven mechanisms (implicit equals implicitfast there, Euler lies
beneath implicitfast)."""
TC_LADDER = (2.0, 4.0, 8.0, 16.0)
"""RK4's time constant in steps, swept at the default step; at 10 times finer, from 8 steps (2 steps
is dominated there: the accelerations stay on the 2-step error whatever the step)."""
IMPEDANCES = (0.99,)
"""Softer impedances swept at the default."""
STEP_BUDGET = 1.0e5
"""Steps over the horizon above which a rung is left out."""


def rule_default(scenario: Scenario) -> Setting:
    """RK4 at the rule's step, tc = TC_STEPS steps, the stiffest impedance."""
    dt = rule_step(scenario, STEPS_PER_PERIOD)
    return Setting.of("RK4", dt=dt, tc=TC_STEPS * dt, impedance=IMPEDANCE)


def rule_ladder(scenario: Scenario, modes: tuple[str, ...], closes_loops: bool) -> list[Setting]:
    """Each of `modes` over its ladder within the budget, then (where a loop is closed) RK4's time
    constant at two steps and the impedance at the default."""
    default = rule_default(scenario)
    weight = max(1.0, len(scenario.bodies) / 8)
    settings = []
    for mode in modes:
        for n in LADDERS[mode]:
            dt = rule_step(scenario, n)
            if n == LADDERS[mode][0] or scenario.t_end / dt * weight <= STEP_BUDGET:
                settings.append(Setting(mode, default.options).replace(dt=dt, tc=TC_STEPS * dt))
    if closes_loops:
        for per_period in (STEPS_PER_PERIOD, 10 * STEPS_PER_PERIOD):
            dt = rule_step(scenario, per_period)
            if per_period != STEPS_PER_PERIOD and scenario.t_end / dt * weight > STEP_BUDGET:
                continue
            ladder = TC_LADDER if per_period == STEPS_PER_PERIOD else [k for k in TC_LADDER if k >= 8.0]
            settings += [default.replace(dt=dt, tc=k * dt) for k in ladder if k != TC_STEPS]
        settings += [default.replace(impedance=imp) for imp in IMPEDANCES]
    return list(dict.fromkeys(settings))


def time_constant(setting: Setting, dt: float) -> float:
    """The equalities' time constant in seconds: `tc`, else `tc_steps` steps (the older option),
    else TC_STEPS steps."""
    if setting.get("tc") is not None:
        return float(setting["tc"])
    return float(setting.get("tc_steps", TC_STEPS)) * dt


STRESS_STEPS = (2e-3, 1e-3, 3e-4, 1e-4, 3e-5)
"""The steps (s) of the stiffness probe, after the scenario's own output step."""
STRESS_TC_STEPS = (2.0, 10.0, 50.0)
"""The stiffness probe's time constants, in steps."""
STRESS_IMPEDANCES = (0.9, 0.99, 0.9999)
"""The stiffness probe's impedances (solimp)."""


def probe_settings(probe: Probe, scenario: Scenario, default: Setting) -> list[Setting] | None:
    """MuJoCo's settings for a stress case (adapters.probes), its `default` first. Stiffness: the
    soft equalities' time constant (in steps) and impedance against the step, RK4 and implicitfast.
    Mass: the default and a ten times finer step, the result depending on the masses."""
    if probe == STIFFNESS:
        interval = scenario.t_end / scenario.steps
        grid = [
            Setting(mode, default.options).replace(dt=dt, tc=tc * dt, impedance=impedance)
            for mode in KINEMATIC_MODES
            for dt in (interval, *STRESS_STEPS)
            for tc in STRESS_TC_STEPS
            for impedance in STRESS_IMPEDANCES
        ]
        return [default, *grid]
    if probe == MASS:
        return [default, at_step(default, float(default["dt"]) / 10)]
    return None
