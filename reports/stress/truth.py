"""The stress suite's truth: the family's closed form wherever the case is a family's mechanism, the
native solver, made to say where it has no answer, elsewhere.

- A case that is a family's own mechanism with its parameters (scenarios.closed_form.exact: the
  speed, scale, link-ratio, mass, long and singular variants of slider_crank and four_bar, the gear
  ratio, the eccentric disc cams) takes the closed form, labelled CLOSED_FORM like the default
  suite's rows, so that the native solver is measured there as every engine is.
- A declared singular case (reports.stress.cases: `singular`) has its closed form up to its singular
  time and NaN from there on: no truth exists past a singular configuration, and no error is
  measured there.
- Elsewhere (spline and lobed cams, a scenario file that takes a case's name) the truth is the native
  solver (reports.scoring.truth.partial_truth), on a grid `refine` times finer where the case asks,
  so that it follows the branch where the scenario's grid would let the solver's predictor jump;
  where it stops (a singular configuration, no configuration beyond), it is NaN from that time.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from reports.scoring import CLOSED_FORM, TRUTH_TOLERANCE, closed_form, partial_truth
from reports.stress.cases import StressCase, case
from scenarios.identity import family_twin
from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory

__all__ = ["declared_case", "partial_truth", "stress_truth", "stress_truth_name"]


def declared_case(scenario: Scenario) -> StressCase:
    """The stress case `scenario` is: its name's declaration when it is that built-in mechanism
    (by digest), a bare case otherwise (a file that takes a case's name is another mechanism, and
    never gets a singular time it may not have)."""
    return case(scenario.name) if family_twin(scenario) is not None else StressCase(scenario.name, "")


def stress_truth(scenario: Scenario, times: np.ndarray) -> Trajectory:
    """The truth of `scenario` on `times` (the runner's truth hook for the stress suite)."""
    declared = declared_case(scenario)
    grid = np.asarray(times, dtype=float)
    with np.errstate(invalid="ignore", divide="ignore"):  # past a singular time: NaN, cut below
        exact = closed_form(scenario, grid)
    if exact is None:
        return partial_truth(scenario, grid, declared.refine)
    singular = declared.singular_time()
    return exact if singular is None else _until(exact, grid < singular)


def stress_truth_name(scenario: Scenario) -> str:
    """What the stress truth of `scenario` is, for the rows measured against it: CLOSED_FORM, or the
    native solve with its tolerance and refinement."""
    if closed_form(scenario, np.zeros(1)) is not None:
        return CLOSED_FORM
    refine = declared_case(scenario).refine
    return f"native, tolerance {TRUTH_TOLERANCE:g}" + (f", grid refined {refine}x" if refine > 1 else "")


def _until(truth: Trajectory, known: np.ndarray) -> Trajectory:
    """`truth` where `known`, NaN elsewhere (every level and extra)."""

    def cut(values: np.ndarray | None) -> np.ndarray | None:
        if values is None:
            return None
        out = np.array(values, dtype=float)
        out[~known] = np.nan
        return out

    levels = {level: cut(truth.level(level)) for level in truth.levels}
    extras = {name: cut(values) for name, values in truth.extras.items()}
    return dataclasses.replace(truth, extras=extras, **levels)  # type: ignore[arg-type]
