"""A dynamic run farther from its truth than the mechanism's size is `diverged`, not `ok`, with the
figure and the limit in its message; a kinematic run and a dynamic run within the size are kept
as the engine said, and a run with no truth to measure by is not judged."""

from __future__ import annotations

import math

import pytest

import scenarios
from adapters.base import RunResult, Setting
from reports.run.rows import result_row
from reports.scoring.divergence import LOST_LIMIT


def row(name: str, position_error: float, status: str = "ok") -> dict:  # type: ignore[type-arg]
    scenario = scenarios.load(name)
    result = RunResult("pinocchio", "4.1.0", Setting.of("baumgarte", dt=4.4857e-4), status, "")  # type: ignore[arg-type]
    metrics = {"error_position": position_error, "constraint_residual": 1e-9}
    return result_row(scenario, result, False, 1, 0, metrics, ("position",))


def test_a_dynamic_run_off_by_more_than_its_mechanism_is_diverged() -> None:
    made = row("n_four_bar", 12.85)  # the shipped baseline's cell: 12.85 lengths off, stored `ok`
    assert made["status"] == "diverged"
    assert "lost: position error 12.8 characteristic lengths" in made["message"]
    assert f"(limit {LOST_LIMIT:g})" in made["message"] and made["self_check"] == ""


@pytest.mark.parametrize(
    ("name", "error"),
    [("n_four_bar", 0.99), ("n_four_bar", math.nan), ("slider_crank", 12.85), ("compound_pendulum", 1.0)],
)
def test_within_the_size_no_truth_or_kinematic_the_engine_s_status_stands(name: str, error: float) -> None:
    made = row(name, error)
    assert made["status"] == "ok" and "lost" not in made["message"]


def test_an_engine_s_own_failure_is_left_as_it_said() -> None:
    made = row("n_four_bar", math.nan, status="diverged")
    assert made["status"] == "diverged" and made["message"] == ""
