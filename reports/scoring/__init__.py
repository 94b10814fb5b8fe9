"""Scoring a trajectory: the truths it is measured against, its per-level errors, the engines'
agreement, energy drift, forces, and the checks a run makes of itself with no truth."""

from typing import TYPE_CHECKING

from reports.face import load

if TYPE_CHECKING:
    from reports.scoring import self_check
    from reports.scoring.agreement import pair_differences, widest
    from reports.scoring.assembly import consistent_start
    from reports.scoring.comparison import measure
    from reports.scoring.divergence import lost
    from reports.scoring.energy_drift import DRIFT_DEFINITION, drift_series
    from reports.scoring.forces import FORCE_DEFINITION, TRUTH_TOLERANCE
    from reports.scoring.level_error import LEVEL_COLUMNS, SCALE_DEFINITION, characteristic_rate, level_series
    from reports.scoring.metrics import HEADLINE_DEFINITION, METRIC_COLUMNS, Residual, headline_series
    from reports.scoring.self_check import step_halving
    from reports.scoring.startup import STARTUP_DEFINITION
    from reports.scoring.truth import (
        CLOSED_FORM,
        DYNAMIC_RTOL,
        NamedTruth,
        closed_form,
        independent_truth,
        named,
        partial_truth,
    )

__all__ = [
    "CLOSED_FORM",
    "DRIFT_DEFINITION",
    "DYNAMIC_RTOL",
    "FORCE_DEFINITION",
    "HEADLINE_DEFINITION",
    "LEVEL_COLUMNS",
    "METRIC_COLUMNS",
    "SCALE_DEFINITION",
    "STARTUP_DEFINITION",
    "TRUTH_TOLERANCE",
    "NamedTruth",
    "Residual",
    "characteristic_rate",
    "closed_form",
    "consistent_start",
    "drift_series",
    "headline_series",
    "independent_truth",
    "level_series",
    "lost",
    "measure",
    "named",
    "pair_differences",
    "partial_truth",
    "self_check",
    "step_halving",
    "widest",
]


def __getattr__(name: str) -> object:
    return load(__name__, name)
