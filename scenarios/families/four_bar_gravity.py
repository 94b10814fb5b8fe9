"""The catalogue's four-bar (crank O2-A, coupler A-B, rocker O4-B, links of 1 kg/m) released from
rest under gravity: no driver, no friction, so T + V stays constant; the frictionless energy check."""

from __future__ import annotations

from scenarios.families.released import released
from scenarios.registry import Family
from scenarios.scenario import ParameterValue, Scenario, require_finite


def _build(p: dict[str, ParameterValue], variant: str) -> Scenario:
    gravity = float(p["gravity"])
    require_finite("four_bar_gravity", gravity=gravity)
    return released(
        "four_bar",
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
    defaults={"theta0": 0.3, "branch": 1, "gravity": 9.81, "t_end": 1.0, "steps": 200},
    build=_build,
    variants={},
    dynamic=True,
)
