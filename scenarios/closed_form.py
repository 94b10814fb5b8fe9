"""The closed-form truth of a scenario: its family's own closed form (`Family.closed_form`, declared
beside the family in scenarios/families/), given only for the mechanism the family builds.

Each family's closed form is derived independently of the native solver: angles from the classical
geometric solutions (triangle closures, inverse trigonometry), rates from differentiating the loop
equations by hand (scenarios.link_kinematics). It returns a Trajectory of every body of the scenario,
all three levels, and the contact parameter phi of cams as the extra `contact.phi` (positions only).
The truth is never another mechanism's: `exact` gives it only to a family's own mechanism.
"""

from __future__ import annotations

import numpy as np

from scenarios.family import NoClosedForm
from scenarios.identity import family_twin
from scenarios.registry import all_families
from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory

__all__ = ["NoClosedForm", "exact"]


def exact(scenario: Scenario, times: np.ndarray | list[float] | None = None) -> Trajectory:
    """The closed-form trajectory of `scenario` (eccentric disc profiles only for cams).

    Only a family's own mechanism has one: `scenario` must be what the family builds from the
    parameters it records (scenarios.identity.family_twin, by digest). A file that takes a family's
    name, or an export edited after it was written, is another mechanism, whatever its
    `[parameters]` table says, and gets NoClosedForm."""
    family = all_families().get(scenario.family)
    if family is None or family.closed_form is None:
        raise NoClosedForm(f"{scenario.name}: no closed form: not a family with one")
    twin = family_twin(scenario)
    if twin is None:
        raise NoClosedForm(
            f"{scenario.name}: no closed form: not the mechanism the family {scenario.family} builds "
            "from the parameters it records"
        )
    grid = np.asarray(scenario.times() if times is None else times, dtype=float)
    return family.closed_form(twin, grid)  # the twin carries the family's parameters
