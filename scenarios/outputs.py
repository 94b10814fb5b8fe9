"""Scenario-level extra outputs: named quantities a scenario asks to be reported beside its bodies'
coordinates, computed from them."""

from __future__ import annotations

from dataclasses import dataclass

from scenarios.bodies import GROUND


@dataclass(frozen=True)
class AngleOutput:
    """Column `name` = theta_body - theta_relative_to (the ground's angle is 0): an absolute or a
    joint angle, continuous like the body angles it is made of."""

    name: str
    body: str
    relative_to: str = GROUND
