"""The result columns that differ between two runs of the same settings: what was timed, when, where
and how many runs were made at once. Tests that compare two runs' rows (serial against Dask, warm
against cold workers, kept workers) compare every other column."""

from __future__ import annotations

from tests.support.stores import RUN_TIMES, WHERE_AND_WHEN

VARIES_BETWEEN_RUNS: tuple[str, ...] = (*RUN_TIMES, *WHERE_AND_WHEN, "revision")
