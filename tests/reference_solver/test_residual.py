"""The constraint residual of a trajectory: the compiled rows give the plain rows' value, and the
value is the constraints' own (zero on a closed form, the known offset of a displaced body)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import scenarios
from reference_solver.residual import constraint_residual, plain_constraint_residual
from scenarios.closed_form import exact

COMPILED = [
    "slider_crank",
    "four_bar",
    "planetary_gears",
    "rack_pinion",
    "four_bar_chain",
    "andrews_squeezer",
]


@pytest.mark.parametrize("name", COMPILED)
def test_compiled_and_plain_rows_give_one_residual_on_random_states(name: str) -> None:
    scenario = scenarios.load(name, {"steps": 40}) if name != "andrews_squeezer" else scenarios.load(name)
    rng = np.random.default_rng(7)
    times = np.asarray(scenario.times())
    bodies = tuple(b.name for b in scenario.bodies)
    length = scenario.characteristic_length
    position = rng.normal(scale=length, size=(len(times), len(bodies), 3))
    trajectory = scenarios.Trajectory(times, bodies, position=position)
    fast, plain = constraint_residual(scenario, trajectory), plain_constraint_residual(scenario, trajectory)
    assert np.all(plain > 1e-3)  # random states are far off the constraints
    np.testing.assert_allclose(fast, plain, rtol=1e-13, atol=0)


def test_the_residual_of_the_closed_form_is_round_off_and_a_displaced_crank_shows() -> None:
    scenario = scenarios.load("slider_crank", {"steps": 24})
    truth = exact(scenario, np.asarray(scenario.times()))
    assert np.max(constraint_residual(scenario, truth)) < 1e-14
    crank = truth.bodies.index("crank")
    assert truth.position is not None
    moved = truth.position.copy()
    moved[:, crank, 0] += 1e-6 * scenario.characteristic_length  # the crank's pin opens by 1e-6 L
    shifted = dataclasses.replace(truth, position=moved)
    np.testing.assert_allclose(constraint_residual(scenario, shifted), 1e-6, rtol=1e-6)
