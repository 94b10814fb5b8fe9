"""The result columns that differ between two runs of the same settings: what was timed, when, where
and how many runs were made at once. Tests that compare two runs' rows (serial against Dask, warm
against cold workers, kept workers) compare every other column."""

from __future__ import annotations

from reports.harness.columns import WALL_COLUMNS

VARIES_BETWEEN_RUNS: tuple[str, ...] = (
    "build_time",
    "run_time",
    "warmup_time",
    "repeats_time",
    *(column.name for column in WALL_COLUMNS),
    "recorded_at",
    "host",
    "workers",
    "revision",
)
