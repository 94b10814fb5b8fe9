"""How the engine tests compute their native dynamic truth."""

from __future__ import annotations

from reports.dynamics.cases import SINGULAR_PASSAGES
from scenarios import Scenario


def compiled(scenario: Scenario) -> bool:
    """Whether the truth may use the compiled constraints, as the dynamics suite's truth does: not
    through a singular passage, where round-off picks the motion (reports.dynamics.cases)."""
    return scenario.family not in SINGULAR_PASSAGES
