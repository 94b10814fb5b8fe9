"""Drake's settings by the one rule (adapters.step_rule): the discrete plant steps a fixed number of
steps per shortest period of the motion, shortened so that every output falls on a step.

The knobs: the step `dt`; the PD drive's gains `kp`, `kd` (N m / rad and N m s / rad, or N / m and
N s / m on a sliding joint); the drive's `lead` (its target sampled at t + lead * dt, which the
implicit PD reaches at the step's end); and how the velocity is read (`velocity`: `central`, or
`state`, the plant's state as it is). SAP's near-rigid threshold changes none of the errors here (the
loops and the drive are stiffer than it either way), so it is not a knob.
"""

from __future__ import annotations

from adapters.base import Setting
from adapters.drake.simulation import CENTRAL, STATE
from adapters.step_rule import rule_step
from scenarios.scenario import Scenario

SAP = "sap"
STEPS_PER_PERIOD = 1000
"""Drake's constant of the rule: steps per shortest period."""
PER_PERIOD = (100, 300, 1000, 3000, 10000)
"""Steps per shortest period in the ladder."""
STEP_BUDGET = 2.0e4
"""Steps over the horizon above which a ladder rung is left out (the first rung always stays)."""
KP, KD = 1.0e9, 1.0e5
"""The drive's gains: stiff enough that SAP's near-rigid regularisation, not the gain, sets the
drive's compliance (the PD is implicit in SAP, so no gain is unstable)."""
GAINS = ((1.0e6, 1.0e3),)
"""Softer drive gains swept at the default step."""


def rule_setting(
    scenario: Scenario, steps_per_period: float = STEPS_PER_PERIOD, **knobs: float | str
) -> Setting:
    """The SAP mode at `steps_per_period` steps per shortest period with the default knobs."""
    values: dict[str, float | str] = {
        "dt": rule_step(scenario, steps_per_period),
        "kp": KP,
        "kd": KD,
        "lead": 1.0,
        "velocity": CENTRAL,
    }
    values.update(knobs)
    return Setting.of(SAP, **values)


def untuned(scenario: Scenario) -> Setting:
    """Drake's defaults at the rule's step: the drive's target at the step's start (what a user
    feeding the trajectory's current value gets) and the plant's state velocity read as it is."""
    return rule_setting(scenario, lead=0.0, velocity=STATE)


def ladder(scenario: Scenario) -> list[Setting]:
    """The step over PER_PERIOD within the budget, then (where a drive acts) softer drive gains at
    the default step."""
    settings = [
        rule_setting(scenario, n)
        for n in PER_PERIOD
        if n == PER_PERIOD[0] or scenario.t_end / rule_step(scenario, n) <= STEP_BUDGET
    ]
    if scenario.analysis == "dynamic":
        return settings  # free dynamics: no drive, so its gains change nothing
    return settings + [rule_setting(scenario, kp=kp, kd=kd) for kp, kd in GAINS]
