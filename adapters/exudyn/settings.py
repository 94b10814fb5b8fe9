"""Exudyn's settings by the one rule (adapters.step_rule): generalized-alpha (index 3) at a fixed
number of steps per shortest period of the motion (the march shortens it to put the outputs on its
steps: adapters.lattice.outputs_on_steps).

The ladder runs each implicit integrator (generalized-alpha at spectral radius 0.9 and 0.5, with full
and with Exudyn's modified Newton; the index-2 trapezoidal rule) over rungs of steps per period,
and GA3's spectral radius at the default step (RHOS); kinematic scenes add GA3 without its run-in
at the default step (the start-up transient the run-in removes, shown as its own row:
adapters.exudyn.run_in) and the static solve per output time. A rung whose run would take more
than STEP_BUDGET steps over the horizon (weighted by bodies / 8 above 8 bodies) is left out, the
coarsest always kept: past it the error sits on the integrator's floor (positions to Newton's
tolerance, velocities O(h^2)) or costs seconds for nothing new.
"""

from __future__ import annotations

from adapters.base import Setting
from adapters.step_rule import rule_step
from scenarios.scenario import Scenario

STEPS_PER_PERIOD = 2000
"""Exudyn's constant of the rule."""
LADDERS = {
    "GA3": (200, 600, 2000, 6000, 20000),
    "GA3-rho0.5": (600, 2000),
    "GA3-modified": (600, 2000),
    "TR2": (200, 600, 2000, 6000),
}
"""Steps per shortest period in the ladder, per mode."""
RHOS = (0.0, 0.6)
"""GA3's spectral radius swept at the default step beside the modes' 0.9 and 0.5."""
STEP_BUDGET = 6.0e4
"""Steps over the horizon above which a rung is left out."""


def rule_default(scenario: Scenario) -> Setting:
    """GA3 at the rule's step."""
    return Setting.of("GA3", dt=rule_step(scenario, STEPS_PER_PERIOD))


def rule_untuned(scenario: Scenario) -> Setting:
    """Exudyn's own default settings at the rule's step."""
    return Setting.of("untuned", dt=rule_step(scenario, STEPS_PER_PERIOD))


def rule_ladder(scenario: Scenario) -> list[Setting]:
    """Each mode over its ladder within the budget, GA3's spectral radius at the default step, and
    (kinematic scenes) the static solve."""
    weight = max(1.0, len(scenario.bodies) / 8)
    settings = [
        Setting.of(mode, dt=rule_step(scenario, n))
        for mode, ladder in LADDERS.items()
        for n in ladder
        if n == ladder[0] or scenario.t_end / rule_step(scenario, n) * weight <= STEP_BUDGET
    ]
    settings += [rule_default(scenario).replace(rho=rho) for rho in RHOS]
    if scenario.analysis != "dynamic":
        settings += [rule_default(scenario).replace(run_in=0), Setting.of("STATIC")]
    return settings
