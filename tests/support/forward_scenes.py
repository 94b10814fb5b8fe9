"""Scenes for forward dynamics' tests: a rod and the swinging four-bar, with the tolerance and the
repartition fraction they are run at."""

from __future__ import annotations

import dataclasses
from typing import Any

import scenarios
from scenarios import Harmonic, Scenario
from scenarios.forces import AppliedTorque

RTOL = 1e-9
FRACTION = 0.95


def swinging_four_bar(driven: bool = False) -> Scenario:
    """The released four-bar; `driven`: a harmonic torque on its crank too (a load that depends on
    time, so that the state at a repartition must be taken at the event's time)."""
    scenario = scenarios.build("four_bar_gravity", overrides={"t_end": 0.25, "steps": 5})
    if not driven:
        return scenario
    return dataclasses.replace(
        scenario, forces=(AppliedTorque("motor", "crank", Harmonic(0.0, 0.05, 20.0, 0.0)),)
    )


def rod(**changes: Any) -> Scenario:
    """compound_pendulum's one link pinned at its end, from 0.3 rad."""
    return dataclasses.replace(
        scenarios.build("compound_pendulum", overrides={"links": 1, "theta0": 0.3}), **changes
    )
