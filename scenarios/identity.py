"""Which mechanism a scenario is: a short digest of its canonical file text, and whether it is
the built-in family its name claims.

A scenario file chooses its own `name`, and its `[parameters]` table only records where it came
from: neither says which mechanism the file describes. The digest does (the SHA-256 of `mbxval
export --format toml`'s text, 12 hex digits). A scenario is its family's own (`family_twin`) when
the family rebuilt from the scenario's parameters has the same digest, on the scenario's grid: only
then do the family's closed forms describe it.
"""

from __future__ import annotations

import dataclasses
import hashlib

from scenarios.files import scenario_toml
from scenarios.registry import build
from scenarios.scenario import Scenario, ScenarioError

DIGEST_LENGTH = 12


def digest(scenario: Scenario) -> str:
    """The scenario's identity: the start of the SHA-256 of its canonical scenario file (a swept
    point's file without the point's name tag: its parameters are in the file)."""
    mechanism = dataclasses.replace(scenario, point=())
    return hashlib.sha256(scenario_toml(mechanism).encode()).hexdigest()[:DIGEST_LENGTH]


def family_twin(scenario: Scenario) -> Scenario | None:
    """The built-in family's scenario built from `scenario`'s own family name, variant and
    parameters, when it is the same mechanism (same digest; the time grid and the description
    are not the mechanism and are taken from `scenario`); None when it is not, or cannot be built."""
    try:
        rebuilt = build(scenario.family, scenario.variant, dict(scenario.parameters))
        twin = dataclasses.replace(
            rebuilt, t_end=scenario.t_end, steps=scenario.steps, description=scenario.description
        )
        return twin if digest(twin) == digest(scenario) else None
    except ScenarioError:
        return None
