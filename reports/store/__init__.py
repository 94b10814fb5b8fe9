"""The results store: the declared columns, the rows and trajectories on disk, written whole or not
at all under one writer's lock, with their provenance, repair and the scenarios' identities.

The column declarations re-export what the measured columns mean (declared beside the measures in
reports.scoring), so that a report reads this face alone."""

from typing import TYPE_CHECKING

from reports.face import load

if TYPE_CHECKING:
    from reports.store import provenance, scenario_identity
    from reports.store.atomic_write import atomic_output, atomic_path, output_target, write_text
    from reports.store.columns import (
        CLOSED_FORM,
        DRIFT_DEFINITION,
        DRIFT_SERIES,
        ERROR_SERIES,
        FORCE_DEFINITION,
        LEVEL_COLUMNS,
        LOST,
        NOT_RECORDED,
        NOT_RUN,
        SCALE_DEFINITION,
        WALL_COLUMNS,
        Judgement,
        empty_row,
    )
    from reports.store.files import committed
    from reports.store.layout import SCHEMA_VERSION, StoreDamaged
    from reports.store.lock import StoreBusy, WriterLock
    from reports.store.repair import Repair, holds_a_store
    from reports.store.results_store import (
        TRUTH,
        Key,
        ResultsStore,
        read_results,
        read_trajectories,
        results_directory,
        stored_truths,
    )
    from reports.store.scenario_identity import stored_scenario

__all__ = [
    "CLOSED_FORM",
    "DRIFT_DEFINITION",
    "DRIFT_SERIES",
    "ERROR_SERIES",
    "FORCE_DEFINITION",
    "LEVEL_COLUMNS",
    "LOST",
    "NOT_RECORDED",
    "NOT_RUN",
    "SCALE_DEFINITION",
    "SCHEMA_VERSION",
    "TRUTH",
    "WALL_COLUMNS",
    "Judgement",
    "Key",
    "Repair",
    "ResultsStore",
    "StoreBusy",
    "StoreDamaged",
    "WriterLock",
    "atomic_output",
    "atomic_path",
    "committed",
    "empty_row",
    "holds_a_store",
    "output_target",
    "provenance",
    "read_results",
    "read_trajectories",
    "results_directory",
    "scenario_identity",
    "stored_scenario",
    "stored_truths",
    "write_text",
]


def __getattr__(name: str) -> object:
    return load(__name__, name)
