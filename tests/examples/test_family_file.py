"""examples/slider_crank.toml is the built-in family written out: the same scenario, bit for bit."""

from __future__ import annotations

import numpy as np

import scenarios
from reference_solver import solve
from scenarios.closed_form import exact
from scenarios.identity import digest
from tests.support.examples.files import LEVELS, example


def test_slider_crank_file_is_the_family() -> None:
    from_file, family = example("slider_crank"), scenarios.build("slider_crank")
    assert digest(from_file) == digest(family)  # the same mechanism (the file records no parameters)
    solved_file, solved_family = solve(from_file), solve(family)
    for level in LEVELS:
        assert np.array_equal(solved_file.level(level), solved_family.level(level)), level


def test_slider_crank_file_against_closed_form() -> None:
    scenario = example("slider_crank")
    solved, expected = solve(scenario), exact(scenario)
    for level in LEVELS:
        assert np.max(np.abs(solved.level(level) - expected.level(level))) < 1e-10 * max(  # type: ignore[operator]
            1.0,
            float(np.max(np.abs(expected.level(level)))),  # type: ignore[arg-type]
        )
