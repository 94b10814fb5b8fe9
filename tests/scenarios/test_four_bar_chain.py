"""The chain of parallelogram four-bar loops: its build, and its solution against the closed form."""

from __future__ import annotations

import math

import numpy as np
import pytest

import scenarios
from reference_solver import solve
from scenarios import ScenarioError
from scenarios.closed_form import exact


@pytest.mark.parametrize("loops", [1, 4, 40])
def test_chain_matches_the_closed_form(loops: int) -> None:
    scenario = scenarios.build("four_bar_chain", overrides={"loops": loops})
    solved, expected = solve(scenario), exact(scenario)
    assert solved.bodies == expected.bodies
    for level in ("position", "velocity", "acceleration"):
        values = getattr(expected, level)
        error = float(np.max(np.abs(getattr(solved, level) - values)))
        assert error < 1e-12 * max(1.0, float(np.max(np.abs(values)))), level


def test_other_lengths_and_swing() -> None:
    overrides = {"loops": 3, "link_length": 0.3, "coupler_length": 0.12, "amplitude": 0.4, "theta0": 1.0}
    scenario = scenarios.build("four_bar_chain", overrides=overrides)
    solved, expected = solve(scenario), exact(scenario)
    np.testing.assert_allclose(solved.position, expected.position, rtol=0, atol=1e-12)  # type: ignore[arg-type]
    np.testing.assert_allclose(solved.acceleration, expected.acceleration, rtol=0, atol=1e-10)  # type: ignore[arg-type]


def test_chain_bodies_and_joints() -> None:
    scenario = scenarios.build("four_bar_chain", overrides={"loops": 3})
    assert scenario.body_names == (
        "crank",
        "coupler_1",
        "rocker_1",
        "coupler_2",
        "rocker_2",
        "coupler_3",
        "rocker_3",
    )
    assert [j.name for j in scenario.joints] == ["O0", "A1", "B1", "O1", "A2", "B2", "O2", "A3", "B3", "O3"]
    assert scenario.characteristic_length == 0.1
    assert scenario.t_end == pytest.approx(2 * math.pi / 10.0)


@pytest.mark.parametrize(("key", "value"), [("loops", 0), ("link_length", -0.1), ("omega", 0.0)])
def test_bad_parameters_are_refused(key: str, value: float) -> None:
    with pytest.raises(ScenarioError, match=key):
        scenarios.build("four_bar_chain", overrides={key: value})
