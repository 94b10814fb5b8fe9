"""Scoring a trajectory: the truths it is measured against, its per-level errors, the engines'
agreement, energy drift, forces, and the checks a run makes of itself with no truth."""

from typing import TYPE_CHECKING

from reports.face import load

if TYPE_CHECKING:  # the face: what the package offers, each loaded on first use (reports.face)
    from reports.scoring import self_check as self_check
    from reports.scoring.agreement import pair_differences as pair_differences
    from reports.scoring.agreement import widest as widest
    from reports.scoring.assembly import consistent_start as consistent_start
    from reports.scoring.comparison import measure as measure
    from reports.scoring.divergence import lost as lost
    from reports.scoring.energy_drift import DRIFT_DEFINITION as DRIFT_DEFINITION
    from reports.scoring.energy_drift import drift_series as drift_series
    from reports.scoring.forces import FORCE_DEFINITION as FORCE_DEFINITION
    from reports.scoring.forces import TRUTH_TOLERANCE as TRUTH_TOLERANCE
    from reports.scoring.level_error import LEVEL_COLUMNS as LEVEL_COLUMNS
    from reports.scoring.level_error import SCALE_DEFINITION as SCALE_DEFINITION
    from reports.scoring.level_error import characteristic_rate as characteristic_rate
    from reports.scoring.level_error import level_series as level_series
    from reports.scoring.metrics import HEADLINE_DEFINITION as HEADLINE_DEFINITION
    from reports.scoring.metrics import METRIC_COLUMNS as METRIC_COLUMNS
    from reports.scoring.metrics import Residual as Residual
    from reports.scoring.metrics import headline_series as headline_series
    from reports.scoring.self_check import step_halving as step_halving
    from reports.scoring.startup import STARTUP_DEFINITION as STARTUP_DEFINITION
    from reports.scoring.truth import CLOSED_FORM as CLOSED_FORM
    from reports.scoring.truth import DYNAMIC_RTOL as DYNAMIC_RTOL
    from reports.scoring.truth import NamedTruth as NamedTruth
    from reports.scoring.truth import closed_form as closed_form
    from reports.scoring.truth import independent_truth as independent_truth
    from reports.scoring.truth import named as named
    from reports.scoring.truth import partial_truth as partial_truth


def __getattr__(name: str) -> object:
    return load(__name__, name)
