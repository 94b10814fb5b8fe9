"""A run of a published benchmark's scene carries that benchmark's own figures in its row
(benchmark_error, benchmark_limit, invariant_error: Family.criterion); other scenes leave them NaN."""

from __future__ import annotations

import math

import adapters
import scenarios
from reference_solver.dynamics import simulate
from reports.scoring.comparison import measure
from reports.store.columns import empty_row

FIGURES = ("benchmark_error", "benchmark_limit", "invariant_error")


def test_an_a02_run_is_measured_by_its_specification_and_another_scene_is_not() -> None:
    engine = adapters.load("reference")
    a02 = scenarios.build("n_four_bar", overrides={"t_end": 1.0, "steps": 20})
    metrics, _, note = measure(a02, engine.run(a02), simulate(a02).trajectory(), None)
    assert 0.0 < metrics["benchmark_error"] < metrics["benchmark_limit"] == 1e-3, note
    assert metrics["invariant_error"] < 1e-10
    pendulum = scenarios.build("compound_pendulum", overrides={"t_end": 0.1, "steps": 4})
    metrics, _, _ = measure(pendulum, engine.run(pendulum), simulate(pendulum).trajectory(), None)
    assert not set(FIGURES) & set(metrics)
    assert all(math.isnan(empty_row()[name]) for name in FIGURES)  # declared, NaN by default
