"""The results store: the declared columns, the rows and trajectories on disk, written whole or not
at all under one writer's lock, with their provenance, repair and the scenarios' identities.

The column declarations re-export what the measured columns mean (declared beside the measures in
reports.scoring), so that a report reads this face alone."""

from typing import TYPE_CHECKING

from reports.face import load

if TYPE_CHECKING:  # the face: what the package offers, each loaded on first use (reports.face)
    from reports.store import provenance as provenance
    from reports.store import scenario_identity as scenario_identity
    from reports.store.atomic_write import atomic_output as atomic_output
    from reports.store.atomic_write import atomic_path as atomic_path
    from reports.store.atomic_write import output_target as output_target
    from reports.store.atomic_write import write_text as write_text
    from reports.store.columns import CLOSED_FORM as CLOSED_FORM
    from reports.store.columns import DRIFT_DEFINITION as DRIFT_DEFINITION
    from reports.store.columns import DRIFT_SERIES as DRIFT_SERIES
    from reports.store.columns import ERROR_SERIES as ERROR_SERIES
    from reports.store.columns import FORCE_DEFINITION as FORCE_DEFINITION
    from reports.store.columns import LEVEL_COLUMNS as LEVEL_COLUMNS
    from reports.store.columns import LOST as LOST
    from reports.store.columns import NOT_RECORDED as NOT_RECORDED
    from reports.store.columns import NOT_RUN as NOT_RUN
    from reports.store.columns import SCALE_DEFINITION as SCALE_DEFINITION
    from reports.store.columns import WALL_COLUMNS as WALL_COLUMNS
    from reports.store.columns import Judgement as Judgement
    from reports.store.columns import empty_row as empty_row
    from reports.store.files import committed as committed
    from reports.store.layout import SCHEMA_VERSION as SCHEMA_VERSION
    from reports.store.layout import StoreDamaged as StoreDamaged
    from reports.store.lock import StoreBusy as StoreBusy
    from reports.store.lock import WriterLock as WriterLock
    from reports.store.repair import Repair as Repair
    from reports.store.repair import holds_a_store as holds_a_store
    from reports.store.results_store import TRUTH as TRUTH
    from reports.store.results_store import Key as Key
    from reports.store.results_store import ResultsStore as ResultsStore
    from reports.store.results_store import read_results as read_results
    from reports.store.results_store import read_trajectories as read_trajectories
    from reports.store.results_store import results_directory as results_directory
    from reports.store.results_store import stored_truths as stored_truths
    from reports.store.scenario_identity import stored_scenario as stored_scenario


def __getattr__(name: str) -> object:
    return load(__name__, name)
