"""Scoring a trajectory made by another tool as if it were one more engine's run.

The trajectory (reports.run.trajectory_file) is measured against the same truth a run gets
(reports.scoring.truth.independent_truth) by the runner's own `measure` (the same metrics, the
per-level errors of reports.scoring.level_error), and becomes a result row with the label as its
engine, the setting IMPORTED and a `measures` text saying where it came from; with a store, the row
and its trajectory are added beside the engines' so the report shows them together.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

import reports.run.recording as recording
from adapters.base import RunResult, Setting
from reports.run.engine_facts import colours, engine_packages
from reports.run.rows import result_row
from reports.run.runner import reference_residual
from reports.run.trajectory_file import ImportedTrajectory
from reports.scoring import (
    HEADLINE_DEFINITION,
    LEVEL_COLUMNS,
    SCALE_DEFINITION,
    NamedTruth,
    Residual,
    independent_truth,
    measure,
)
from reports.store import ResultsStore, provenance
from scenarios.scenario import Level, Scenario

IMPORTED = Setting.of("imported")
"""The setting of every imported row: no mode, no options; the row is the engine's default."""


@dataclass(frozen=True)
class Score:
    """An imported trajectory's result row, the truth it was measured against, and its levels."""

    row: dict[str, Any]
    truth: NamedTruth
    imported: ImportedTrajectory

    def level_error(self, level: Level) -> float:
        """The dimensionless error at `level` (NaN where not scored)."""
        value = self.row.get(LEVEL_COLUMNS[level], math.nan)
        return float(value) if value is not None else math.nan


def measures(imported: ImportedTrajectory) -> str:
    """The `measures` text of an imported row."""
    return (
        f"an imported trajectory ({imported.source}): made outside mbxval, scored against the same "
        "truth with the same metrics as the engines' runs; no timing"
    )


def score(
    scenario: Scenario,
    imported: ImportedTrajectory,
    label: str,
    truth: NamedTruth | None = None,
    residual: Residual | None = None,
) -> Score:
    """The imported trajectory's row: errors against `truth` (default: the independent truth on the
    scenario's grid), residual by `residual` (default: the native solver's, as in a run)."""
    times = imported.trajectory.times
    found = truth if truth is not None else independent_truth(scenario, times)
    scored = dataclasses.replace(scenario, outputs=imported.trajectory.bodies)
    result = RunResult(
        engine=label,
        version="imported",
        setting=IMPORTED,
        status="ok",
        trajectory=imported.trajectory,
        measures=measures(imported),
    )
    metrics, levels, note = measure(
        scored, result, found.trajectory, residual or reference_residual(), found.forces
    )
    row = result_row(scenario, result, True, 0, 0, metrics, levels, "; ".join((*imported.notes, note)))
    row.update(
        truth=found.name,
        force_truth="" if math.isnan(metrics.get("error_force", math.nan)) else found.forces,
        revision=provenance.git_revision(),
        stale=False,
        message=row["message"].strip("; "),
    )
    return Score(row, found, imported)


def add_to_store(store: ResultsStore, scenario: Scenario, scored: Score) -> None:
    """Add the row, its trajectory and the truth to `store` and save it, then record what the
    report draws of it (reports.run.recording: its error over time, the engines' agreement),
    on the store as a report reads it (the caller holds the store's writer lock). The store's
    description is kept; a new store gets the runner's."""
    store.put_truth(scenario.name, scored.truth.name, scored.truth.trajectory.select(scenario.output_bodies))
    store.add(scored.row, scored.imported.trajectory)
    meta = dict(store.meta) or {
        **provenance.describe(engine_packages()),
        "suite": "imported",
        "truth": "each row's `truth` column (reports.scoring.truth)",
        "headline": HEADLINE_DEFINITION,
        "scales": SCALE_DEFINITION,
    }
    label = scored.row["engine"]
    meta["imported"] = {**meta.get("imported", {}), label: scored.imported.source}
    meta["engine_colours"] = {**meta.get("engine_colours", {}), **colours([label])}
    meta["revisions"] = sorted({str(r.get("revision") or "unknown") for r in store.rows.values()})
    store.save(meta, clean=True)
    stored = ResultsStore(store.directory)
    if recording.record(stored):
        stored.save(stored.meta, clean=True)
