"""The stress suite: cases made to break solvers, their truths, and the stability map's verdicts.

`recording` stores the stress cases' and swept points' verdicts when a run is made (it imports the
native solver)."""

from typing import TYPE_CHECKING

from reports.face import load

if TYPE_CHECKING:
    from reports.stress import recording
    from reports.stress.cases import scenario_names, stress_settings
    from reports.stress.truth import stress_truth, stress_truth_name

__all__ = ["recording", "scenario_names", "stress_settings", "stress_truth", "stress_truth_name"]


def __getattr__(name: str) -> object:
    return load(__name__, name)
