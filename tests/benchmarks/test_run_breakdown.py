"""The run-phase breakdown accounts for a real run's overhead step by step (issue #27): a one-row run
of the native engine, its steps timed in this process and in the worker's child, leaves little
unaccounted, and the harness is as it was afterwards."""

from __future__ import annotations

from pathlib import Path

from benchmarks.run_breakdown import breakdown, table
from reports.run import group_runs, runner


def test_a_run_s_overhead_is_accounted_for_step_by_step(tmp_path: Path) -> None:
    measure, solve_truth = group_runs._measure, runner.solve_truth
    found = breakdown(["four_bar"], ["reference"], "quick", tmp_path)
    assert group_runs._measure is measure and runner.solve_truth is solve_truth  # restored
    assert found["rows"] == 1 and 0 < found["work"] < found["wall"]
    lines = dict(found["lines"])
    assert lines["truths (1)"] > 0 and lines["forks (1)"] > 0 and lines["rows"] > 0
    assert all(seconds >= 0 for label, seconds in found["lines"] if label != "unaccounted")
    assert abs(lines["unaccounted"]) < 0.25 * found["wall"]
    text = table(found)
    assert text.startswith("1 rows: run phase") and "child: residual, others (1 runs, " in text
    assert "child: residual, cams (0 runs, 0.00 ms a run)" in text  # each part over its own runs


def test_a_run_that_failed_counts_its_work_and_leaves_nothing_unaccounted(tmp_path: Path) -> None:
    """A dead point: the native run fails (singular) and its row records what it spent getting
    there (adapters.spent), which counts as work; the steps still add up."""
    found = breakdown(["four_bar[crank_length=0.2]"], ["reference"], "quick", tmp_path)
    assert found["rows"] == 1 and 0.0 < found["work"] < found["wall"]
    assert all(seconds == seconds for _, seconds in found["lines"])  # no NaN
    assert abs(dict(found["lines"])["unaccounted"]) < 0.25 * found["wall"]
