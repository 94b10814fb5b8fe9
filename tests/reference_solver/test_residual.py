"""The constraint residual of a trajectory: the compiled rows give the plain rows' value, and the
value is the constraints' own (zero on a closed form, the known offset of a displaced body)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import reference_solver.residual as residual_module
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
    compiled, plain = (
        constraint_residual(scenario, trajectory),
        plain_constraint_residual(scenario, trajectory),
    )
    assert np.all(plain > 1e-3)  # random states are far off the constraints
    np.testing.assert_allclose(compiled, plain, rtol=1e-13, atol=0)


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


@pytest.mark.parametrize("measure", [constraint_residual, plain_constraint_residual])
def test_a_trajectory_without_positions_or_with_missing_bodies_is_refused(measure) -> None:  # type: ignore[no-untyped-def]
    scenario = scenarios.load("slider_crank", {"steps": 4})
    times = np.asarray(scenario.times())
    with pytest.raises(ValueError) as caught:
        measure(scenario, scenarios.Trajectory(times, ("crank",)))
    assert str(caught.value) == "the trajectory has no positions"
    with pytest.raises(ValueError) as caught:
        measure(scenario, scenarios.Trajectory(times, ("crank",), position=np.zeros((len(times), 1, 3))))
    assert str(caught.value) == "the trajectory lacks bodies rod, slider"


def test_a_cams_rows_count_only_when_the_trajectory_carries_its_contact_parameter() -> None:
    """The roller cam's closed form, with its contact parameter: round-off. The parameter moved by
    1e-3 rad: the roller's rows (area rows, over L^2 = 0.0025) move by about R (R + r) 1e-3 / L^2 =
    1.4e-3 to first order (R = 0.05, r = 0.02; the eccentricity 0.01 changes the lever arms along
    the turn), within a factor 3 at every time, on the compiled rows as on the plain ones to round-off
    (test_residual_cams.py). Without the parameter the cam's rows are left out
    and the other rows still close."""
    scenario = scenarios.load("cam_roller", {"steps": 24})
    truth = exact(scenario, np.asarray(scenario.times()))
    assert set(truth.extras) == {"contact.phi"} and scenario.characteristic_length == 0.05
    assert np.max(constraint_residual(scenario, truth)) < 1e-14
    moved = dataclasses.replace(truth, extras={"contact.phi": truth.extras["contact.phi"] + 1e-3})
    residual = constraint_residual(scenario, moved)
    assert np.all(residual > 1.4e-3 / 3) and np.all(residual < 1.4e-3 * 3)
    np.testing.assert_allclose(plain_constraint_residual(scenario, moved), residual, rtol=0, atol=4e-16)
    assert np.max(constraint_residual(scenario, dataclasses.replace(moved, extras={}))) < 1e-14


def test_the_bodies_may_come_in_any_order_and_with_others() -> None:
    """The residual reads each body by name: the closed form's bodies reversed, with an unknown
    body in between, give the same residual (the 1e-6 L crank offset of the test above)."""
    scenario = scenarios.load("slider_crank", {"steps": 24})
    truth = exact(scenario, np.asarray(scenario.times()))
    assert truth.position is not None
    moved = truth.position.copy()
    moved[:, truth.bodies.index("crank"), 0] += 1e-6 * scenario.characteristic_length
    order = list(reversed(range(len(truth.bodies))))
    shuffled = np.concatenate(
        [moved[:, order[:1]], np.full((len(truth.times), 1, 3), 7.0), moved[:, order[1:]]], axis=1
    )
    bodies = (truth.bodies[order[0]], "spare", *(truth.bodies[k] for k in order[1:]))
    other = scenarios.Trajectory(truth.times, bodies, position=shuffled)
    for measure in (constraint_residual, plain_constraint_residual):
        np.testing.assert_allclose(measure(scenario, other), 1e-6, rtol=1e-6)


def test_a_scenario_without_cams_is_measured_on_its_compiled_rows(monkeypatch: pytest.MonkeyPatch) -> None:
    """The plain rows are for checking the compiled ones: where the scenario compiles,
    constraint_residual never evaluates them (about 300 times slower)."""

    def refused(*args: object) -> None:
        raise AssertionError("the plain rows were evaluated")

    monkeypatch.setattr(residual_module, "_plain_residual", refused)
    scenario = scenarios.load("slider_crank", {"steps": 24})
    truth = exact(scenario, np.asarray(scenario.times()))
    assert np.max(constraint_residual(scenario, truth)) < 1e-14
