"""The stress suite: cases made to break solvers, their truths, and the stability map's verdicts.

`recording` stores the stress cases' and swept points' verdicts when a run is made (it imports the
native solver)."""

from typing import TYPE_CHECKING

from reports.face import load

if TYPE_CHECKING:  # the face: what the package offers, each loaded on first use (reports.face)
    from reports.stress import recording as recording
    from reports.stress.cases import scenario_names as scenario_names
    from reports.stress.cases import stress_settings as stress_settings
    from reports.stress.truth import stress_truth as stress_truth
    from reports.stress.truth import stress_truth_name as stress_truth_name


def __getattr__(name: str) -> object:
    return load(__name__, name)
