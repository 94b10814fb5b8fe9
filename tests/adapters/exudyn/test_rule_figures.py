"""docs/settings-rule.md's Exudyn figures recomputed: generalized-alpha's start-up transient on the
four-bar under each remedy, the run-in's length, the transient measured by the start-up rule
(scoring.startup) on the kinematic scenes without the run-in and in free dynamics, each within
tests.support.rule_figures' TOLERANCE, against the harness truth."""

from __future__ import annotations

import dataclasses
import functools

import numpy as np
import pytest

import adapters
import scenarios
from adapters.base import Setting
from adapters.exudyn.run_in import run_in_steps
from reports.scoring.comparison import measure
from reports.scoring.truth import independent_truth
from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory
from tests.support import rule_figures as figures
from tests.support.bounds import held

EXUDYN = adapters.load("exudyn")
FOUR_BAR_OUTPUTS = 2000


@functools.cache
def scene(name: str) -> Scenario:
    built = scenarios.build(name)
    return dataclasses.replace(built, steps=FOUR_BAR_OUTPUTS) if name == "four_bar" else built


@functools.cache
def truth(name: str) -> Trajectory:
    return independent_truth(scene(name), np.asarray(scene(name).times())).trajectory


def metrics(name: str, setting: Setting | None = None) -> dict[str, float]:
    scenario = scene(name)
    run = EXUDYN.run(scenario, setting or EXUDYN.default_setting(scenario), np.asarray(scenario.times()))
    assert run.status == "ok", run.message
    return measure(scenario, run, truth(name), None)[0]


def startup_steps(found: dict[str, float], name: str = "four_bar") -> float:
    return found["startup_time"] / float(EXUDYN.default_setting(scene(name))["dt"])


def hold(values: list[float], measured: list[float], names: tuple[str, ...]) -> None:
    held(values, measured, names, figures.TOLERANCE)


@pytest.mark.parametrize("remedy", list(figures.EXUDYN_REMEDIES))
def test_each_remedy_of_the_four_bar_s_start_up_transient(remedy: str) -> None:
    options, acceleration, steps = figures.EXUDYN_REMEDIES[remedy]
    found = metrics("four_bar", EXUDYN.default_setting(scene("four_bar")).replace(**options))
    hold([found["error_acceleration"]], [acceleration], ("acceleration",))
    if steps == 0:
        assert found["startup_time"] == 0.0, found["startup_time"]
    else:
        hold([startup_steps(found)], [steps], ("start-up steps",))


def test_rho_zero_from_the_exact_start() -> None:
    found = metrics("four_bar", EXUDYN.default_setting(scene("four_bar")).replace(run_in=0, rho=0.0))
    acceleration, steps = figures.EXUDYN_RHO_ZERO
    assert found["error_acceleration"] == pytest.approx(acceleration, rel=figures.TOLERANCE - 1)
    assert round(startup_steps(found)) == steps


def test_index_2_has_no_transient_and_its_positions_drift() -> None:
    found = metrics("four_bar", Setting.of("TR2", dt=EXUDYN.default_setting(scene("four_bar"))["dt"]))
    hold(
        [found["error_position"], found["error_acceleration"]],
        list(figures.EXUDYN_INDEX_2),
        ("position", "acceleration"),
    )
    assert found["startup_time"] == 0.0


def test_the_run_in_is_the_least_n_with_n_rho_to_the_n_below_1e_9() -> None:
    assert run_in_steps(0.9) == figures.EXUDYN_RUN_IN_STEPS
    n = figures.EXUDYN_RUN_IN_STEPS
    assert n * 0.9**n <= 1e-9 < (n - 1) * 0.9 ** (n - 1)


@pytest.mark.parametrize("name", list(figures.EXUDYN_EXACT_START))
def test_the_exact_start_shows_as_the_start_up_figure(name: str) -> None:
    plain = dataclasses.replace(scene(name), steps=scenarios.build(name).steps)
    run = EXUDYN.run(plain, EXUDYN.default_setting(plain).replace(run_in=0), np.asarray(plain.times()))
    assert run.status == "ok", run.message
    found = measure(plain, run, independent_truth(plain, np.asarray(plain.times())).trajectory, None)[0]
    hold(
        [found["startup_excess"], found["startup_time"]],
        list(figures.EXUDYN_EXACT_START[name]),
        ("excess", "time"),
    )


@pytest.mark.parametrize("name", list(figures.EXUDYN_FREE_EXCESS))
def test_free_dynamics_shows_no_transient_above_the_settled_error(name: str) -> None:
    hold([metrics(name)["startup_excess"]], [figures.EXUDYN_FREE_EXCESS[name]], ("excess",))


def test_the_spline_cam_restarts_the_transient_at_each_knot() -> None:
    found = metrics("cam_roller/spline")
    hold([found["error_acceleration"]], [figures.EXUDYN_SPLINE_KNOTS], ("acceleration",))
