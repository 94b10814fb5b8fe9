"""Reading the shipped examples and comparing the native solver with a closed form."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from reference_solver import solve
from scenarios import Scenario, Trajectory
from scenarios.files import read_scenario

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
LEVELS = ("position", "velocity", "acceleration")


def example(name: str) -> Scenario:
    return read_scenario(EXAMPLES / f"{name}.toml")


def max_errors(
    scenario: Scenario, expected: dict[str, tuple[np.ndarray, np.ndarray, np.ndarray]]
) -> dict[str, float]:
    """The largest |native - expected| per level over the listed bodies and the whole grid."""
    solved: Trajectory = solve(scenario)
    errors = {}
    for k, level in enumerate(LEVELS):
        values = solved.level(level)
        assert values is not None
        errors[level] = max(
            float(np.max(np.abs(values[:, solved.bodies.index(body), :] - arrays[k])))
            for body, arrays in expected.items()
        )
    return errors
