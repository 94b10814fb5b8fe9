"""Reading the shipped examples and comparing the native solver (kinematics, or forward dynamics at
the native engine's default setting) with a closed form."""

from __future__ import annotations

from pathlib import Path

import numpy as np

import adapters
from reference_solver import solve
from scenarios import Scenario, Trajectory
from scenarios.files import read_scenario

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"
LEVELS = ("position", "velocity", "acceleration")


def example(name: str) -> Scenario:
    return read_scenario(EXAMPLES / f"{name}.toml")


def native(scenario: Scenario) -> Trajectory:
    """The native solution: kinematics, or forward dynamics at the native engine's default setting."""
    if scenario.analysis != "dynamic":
        return solve(scenario)
    engine = adapters.load("reference")
    result = engine.run(scenario, engine.default_setting(scenario), np.asarray(scenario.times()))
    assert result.status == "ok" and result.trajectory is not None, result.message
    return result.trajectory


def max_errors(
    scenario: Scenario, expected: dict[str, tuple[np.ndarray, np.ndarray, np.ndarray]]
) -> dict[str, float]:
    """The largest |native - expected| per level over the listed bodies and the whole grid."""
    solved = native(scenario)
    errors = {}
    for k, level in enumerate(LEVELS):
        values = solved.level(level)
        assert values is not None
        errors[level] = max(
            float(np.max(np.abs(values[:, solved.bodies.index(body), :] - arrays[k])))
            for body, arrays in expected.items()
        )
    return errors
