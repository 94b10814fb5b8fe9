"""The catalogue's four-bar (crank O2-A, coupler A-B, rocker O4-B, links of 1 kg/m) released from
rest under gravity: no driver, no friction, so T + V stays constant; the frictionless energy check."""

from __future__ import annotations

from scenarios.families import four_bar
from scenarios.families.released import released
from scenarios.family import MAX_GRID_STEPS, Family, Parameter, angle, count, positive
from scenarios.scenario import ParameterValue, Scenario, require_finite


def _build(p: dict[str, ParameterValue], variant: str) -> Scenario:
    gravity = float(p["gravity"])
    require_finite("four_bar_gravity", gravity=gravity)
    return released(
        four_bar.FAMILY,
        {"theta0": p["theta0"], "branch": p["branch"]},
        "four_bar_gravity",
        variant,
        p,
        "four-bar linkage released from rest under gravity",
        gravity=(0.0, -gravity),
    )


FAMILY = Family(
    name="four_bar_gravity",
    summary="the four-bar released from rest under gravity (frictionless: T + V constant)",
    parameters={
        "theta0": angle(0.3),
        "branch": Parameter(1, low=-1, high=1, nonzero=True),
        "gravity": Parameter(9.81, "m/s^2", low=-1e6, high=1e6),
        "t_end": positive(1.0, 1e6, "s"),
        "steps": count(200, 1, MAX_GRID_STEPS),
    },
    build=_build,
    variants={},
    dynamic=True,
)
