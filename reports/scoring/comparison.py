"""One run set against its truth: the error metrics per level, the constraint residual, and what the
scenario adds (energy drift in dynamics, driving forces and reactions where the run reports them),
with a note on whatever could not be measured."""

from __future__ import annotations

import math

import reports.scoring.self_check as self_check
from adapters import NATIVE
from adapters.base import RunResult
from reports.scoring.energy_drift import energy_drift
from reports.scoring.forces import force_columns, force_errors, judges_native
from reports.scoring.level_error import level_errors
from reports.scoring.metrics import Residual, compared_levels, error_metrics, residual_metrics
from reports.scoring.startup import startup
from scenarios import Scenario, all_families
from scenarios.family import Criterion
from scenarios.trajectory import Trajectory


class ComparisonError(Exception):
    """An engine's trajectory that cannot be set against the truth (wrong grid or bodies)."""


def measure(
    scenario: Scenario,
    result: RunResult,
    truth: Trajectory | str,
    residual: Residual | None,
    force_truth: str = "",
) -> tuple[dict[str, float], tuple[str, ...], str]:
    """Error metrics, compared levels and a note (why something is missing) for one run; `force_truth`
    names the truth's forces (a native run's forces are judged only against one not its own)."""
    if result.status != "ok" or result.trajectory is None:
        return {}, (), ""
    if isinstance(truth, str):  # no truth: the run's own figures only (scoring.self_check)
        return {"energy_change": self_check.energy_change(scenario, result.trajectory)}, (), truth
    notes = []
    try:
        metrics = error_metrics(scenario, result.trajectory, truth)
        metrics.update(level_errors(scenario, result.trajectory, truth))
        metrics["error"] = metrics["error_position"]  # one headline: the position level
        levels = compared_levels(scenario, result.trajectory, truth)
        metrics.update(startup(scenario, result.trajectory, truth, levels))
    except (ValueError, KeyError) as error:  # the engine's trajectory is not what it should be
        raise ComparisonError(f"cannot compare with the truth: {error}") from error
    if residual is None:
        notes.append("constraint residual not measured (reference_solver.constraint_residual missing)")
    else:
        try:
            metrics.update(residual_metrics(scenario, result.trajectory, residual))
        except Exception as error:
            notes.append(f"constraint residual failed: {type(error).__name__}: {error}")
            metrics["constraint_residual"] = math.nan
    if scenario.analysis == "dynamic":
        try:
            metrics["energy_drift"] = energy_drift(scenario, result.trajectory, truth)
        except (ValueError, KeyError) as error:
            notes.append(f"energy drift not measured: {error}")
    metrics["energy_change"] = self_check.energy_change(scenario, result.trajectory)  # no truth used
    benchmark = _family_criterion(scenario)
    if benchmark is not None:
        try:
            metrics.update(benchmark(scenario, result.trajectory))
        except (ValueError, KeyError) as error:
            notes.append(f"benchmark criterion not measured: {error}")
    judged = result.engine != NATIVE or judges_native(force_truth)  # never against its own forces
    if force_columns(result.trajectory) and judged:
        native = {c: truth.extras[c] for c in force_columns(truth)}
        if not native:
            notes.append("forces not compared: the truth carries none (scoring.truth.with_native_forces)")
        else:
            try:
                metrics.update(force_errors(scenario, result.trajectory, native))
            except (ValueError, KeyError) as error:
                notes.append(f"forces not compared: {error}")
    elif force_columns(result.trajectory):
        own = f" ({force_truth})" if force_truth else ""
        notes.append(f"forces not compared: the force truth is the native solver's own{own}")
    return metrics, levels, "; ".join(notes)


def _family_criterion(scenario: Scenario) -> Criterion | None:
    """The published benchmark criterion of the scenario's family (Family.criterion), if any."""
    found = all_families().get(scenario.family)
    return found.criterion if found is not None else None
