"""A kinematic family's mechanism set free for dynamics: the same bodies and joints, built by the
kinematic family's own builder and parameters, with its drivers removed and loads added."""

from __future__ import annotations

from dataclasses import replace
from typing import Any

from scenarios.family import Family
from scenarios.scenario import ParameterValue, Scenario


def released(
    kinematic: Family,
    overrides: dict[str, ParameterValue],
    family: str,
    variant: str,
    p: dict[str, ParameterValue],
    description: str,
    **changes: Any,
) -> Scenario:
    """Scenario `family` made of `kinematic` built with `overrides`, without drivers, over
    [0, p["t_end"]] in p["steps"] steps, with the dynamic fields in `changes` (gravity, forces...)."""
    values = {**kinematic.defaults, **overrides}
    params = {key: kinematic.parameters[key].check(kinematic.name, key, v) for key, v in values.items()}
    base = kinematic.build(params, "default")
    return replace(
        base,
        family=family,
        variant=variant,
        drivers=(),
        t_end=float(p["t_end"]),
        steps=int(p["steps"]),
        parameters=tuple(p.items()),
        description=description,
        analysis="dynamic",
        **changes,
    )
