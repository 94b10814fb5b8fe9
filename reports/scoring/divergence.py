"""Whether a dynamic run that ended `ok` has lost the mechanism: farther from its truth than the
mechanism's own size.

A free-dynamics run can end without an engine's complaint and be anywhere: a stiff spring blown up,
a chain through its singular position on the other branch. A position error (in characteristic
lengths, scoring.level_error) above LOST_LIMIT means the run no longer describes the mechanism:
its row is `diverged`, with the figure in its message. The rule also makes such a row's status
independent of round-off: whether an engine stops itself (its own `diverged`) or runs on to a
meaningless end, a run this far off is `diverged` either way, so a gate holds it to one status.
"""

from __future__ import annotations

import math

from reports.scoring.level_error import LEVEL_COLUMNS
from scenarios.scenario import Scenario

LOST_LIMIT = 1.0
"""The largest position error (in characteristic lengths) of an `ok` dynamic run."""


def lost(scenario: Scenario, metrics: dict[str, float]) -> str:
    """'' for a kinematic run or a dynamic one within LOST_LIMIT of its truth; else why it is lost."""
    error = metrics.get(LEVEL_COLUMNS["position"], math.nan)
    if scenario.analysis != "dynamic" or not error > LOST_LIMIT:  # NaN: no truth to measure by
        return ""
    return (
        f"lost: position error {error:.3g} characteristic lengths, farther from the truth than the "
        f"mechanism's size (limit {LOST_LIMIT:g})"
    )
