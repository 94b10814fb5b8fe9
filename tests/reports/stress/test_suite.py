"""The stress suite: every stress variant declared, its truth (the family's closed form wherever the
case is a family's mechanism, up to its singular time; the native solver elsewhere), the native
solver measured against it, its settings hook, and the native solver's accuracy across the scale
and speed extremes against closed forms."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import adapters
import scenarios
from reference_solver import solve
from reports import suites
from reports.scoring.level_error import level_errors
from reports.scoring.truth import CLOSED_FORM, closed_form
from reports.stress.cases import CASES, NOMINAL_SPEED
from reports.stress.truth import partial_truth, stress_truth, stress_truth_name
from scenarios.closed_form import exact
from scenarios.scenario import LEVELS
from scenarios.trajectory import Trajectory
from tests.support.measured import measured_table


def positions(trajectory: Trajectory) -> np.ndarray:
    assert trajectory.position is not None
    return trajectory.position


def test_every_stress_variant_is_a_declared_case_and_none_is_in_the_default_suite() -> None:
    stress = [n for n in scenarios.catalogue(include_stress=True) if "/stress" in n]
    assert stress and set(stress) <= set(CASES)
    assert not set(stress) & set(suites.get("default").scenarios())
    assert suites.get("stress").scenarios() == list(CASES)
    for name in CASES:
        scenarios.build(name)  # every declared case builds


def test_the_stress_suite_has_its_truth_and_settings_hooks() -> None:
    suite = suites.get("stress")
    assert suite.truth is not None and suite.settings is not None and not suite.ladder


def test_a_singular_case_has_a_truth_up_to_its_singular_time_and_none_after() -> None:
    scenario = scenarios.build("slider_crank/stress_dead_centre")
    times = np.asarray(scenario.times())
    truth = stress_truth(scenario, times)
    singular = CASES[scenario.name].singular_time()
    assert singular is not None
    known = np.all(np.isfinite(positions(truth)), axis=(1, 2))
    np.testing.assert_array_equal(known, times < singular)
    expected = exact(scenario, times[known])
    assert np.max(np.abs(positions(truth)[known] - positions(expected))) < 1e-10


NATIVE_AGAINST_CLOSED_FORM = measured_table("stress_native_against_closed_form")
"""Every case of a family's mechanism but the near change point, where the native solver on the
scenario's grid jumps branch (test_a_refined_native_solve_agrees_with_the_closed_form...)."""
CLOSED = [*NATIVE_AGAINST_CLOSED_FORM, "four_bar/stress_near_change_point"]
NATIVE_ONLY = {
    "cam_knife_edge/stress_few_knots": "native, tolerance 1e-12",
    "cam_roller/stress_few_knots": "native, tolerance 1e-12",
    "cam_roller/stress_undercut": "native, tolerance 1e-12, grid refined 4x",
}


def test_every_case_is_either_a_closed_form_case_or_a_native_one() -> None:
    assert set(CLOSED) | set(NATIVE_ONLY) == set(CASES) and not set(CLOSED) & set(NATIVE_ONLY)


@pytest.mark.parametrize("name", CLOSED)
def test_a_family_mechanism_takes_its_closed_form_up_to_its_singular_time(name: str) -> None:
    scenario = scenarios.build(name)
    times = np.asarray(scenario.times())
    assert stress_truth_name(scenario) == CLOSED_FORM
    truth, singular = stress_truth(scenario, times), CASES[name].singular_time()
    known = times < singular if singular is not None else np.ones(times.size, bool)
    expected = exact(scenario, times[known])
    for level in LEVELS:
        values = truth.level(level)
        assert values is not None
        np.testing.assert_array_equal(values[known], expected.level(level))
        assert np.isnan(values[~known]).all()


@pytest.mark.parametrize("name", NATIVE_AGAINST_CLOSED_FORM)
def test_the_native_solver_is_at_round_off_against_the_closed_form(name: str) -> None:
    """The reference engine at its default setting, as the stress suite runs it, up to the singular
    time: each level's error within [measured / 10, 3 x measured] (exactly 0 where it was 0)."""
    scenario = scenarios.build(name)
    times = np.asarray(scenario.times())
    truth = stress_truth(scenario, times)
    known = np.isfinite(positions(truth)).all(axis=(1, 2))
    engine = adapters.load("reference")
    run = engine.simulate(engine.build(scenario, engine.default_setting(scenario)), times[known])
    errors = level_errors(scenario, run, _cut(truth, known), LEVELS)
    for level, measured in zip(LEVELS, NATIVE_AGAINST_CLOSED_FORM[name], strict=True):
        value = errors[f"error_{level}"]
        if measured == 0.0:
            assert value == 0.0, level
        else:
            assert measured / 10 <= value <= 3 * measured, (level, value)


@pytest.mark.parametrize("name", NATIVE_ONLY)
def test_a_case_without_closed_form_keeps_the_native_truth(name: str) -> None:
    scenario = scenarios.build(name)
    assert closed_form(scenario, np.zeros(1)) is None
    assert stress_truth_name(scenario) == NATIVE_ONLY[name]


def test_a_refined_native_solve_agrees_with_the_closed_form_near_the_change_point() -> None:
    """1e-6 m short of a change point the closed form is the truth: the native solver on a grid 16x
    finer follows the same branch to the end (measured 7.5e-14 m; 1e-12 allowed)."""
    scenario = scenarios.build("four_bar/stress_near_change_point")
    times = np.asarray(scenario.times())
    truth, finer = stress_truth(scenario, times), partial_truth(scenario, times, refine=16)
    assert np.all(np.isfinite(positions(truth)))
    assert np.max(np.abs(positions(truth) - positions(finer))) < 1e-12


def _cut(truth: Trajectory, known: np.ndarray) -> Trajectory:
    levels = {level: truth.level(level)[known] for level in LEVELS}  # type: ignore[index]
    return dataclasses.replace(truth, times=truth.times[known], extras={}, **levels)


def _relative_errors(name: str) -> np.ndarray:
    """The native solver against closed forms: position, velocity and acceleration errors,
    lengths over L (L omega, L omega^2) and angles over 1 (omega, omega^2)."""
    scenario = scenarios.build(name)
    solved, expected = solve(scenario), exact(scenario)
    length, omega = scenario.characteristic_length, abs(float(scenario.parameter("omega")))
    out = []
    for k, level in enumerate(LEVELS):
        diff = np.abs(solved.level(level) - expected.level(level))  # type: ignore[operator]
        out.append(max(diff[..., :2].max() / length, diff[..., 2].max()) / omega**k)
    return np.array(out)


SIMILAR = [n for n, c in CASES.items() if c.similar is not None]


@pytest.mark.parametrize("name", SIMILAR)
def test_native_solver_keeps_its_accuracy_across_scales_and_speeds(name: str) -> None:
    """Relative errors within 10x of the nominal case's, both floored at 1e-13 (closed forms
    evaluated in floating point differ from each other by about that)."""
    nominal = np.maximum(_relative_errors("slider_crank"), 1e-13)
    extreme = np.maximum(_relative_errors(name), 1e-13)
    assert np.all(extreme <= 10 * nominal), (extreme, nominal)


def test_speed_cases_give_each_time_stepping_engine_its_nominal_steps_per_revolution() -> None:
    """Every step is stretched by the speed ratio, which is what the rule's default step
    (adapters.step_rule) does on the faster scenario. The kinematic engines have no step."""
    name = "slider_crank/stress_speed_1e-3"
    scenario = scenarios.build(name)
    hook = suites.get("stress").settings
    assert hook is not None
    mujoco, exudyn = adapters.load("mujoco"), adapters.load("exudyn")
    nominal_dt = float(mujoco.default_setting(scenarios.build("slider_crank"))["dt"])
    (setting,) = hook(scenario, mujoco) or []
    assert float(setting["dt"]) == pytest.approx(nominal_dt * NOMINAL_SPEED / 1e-3)
    (setting,) = hook(scenario, exudyn) or []
    assert float(setting["dt"]) == pytest.approx(float(exudyn.default_setting(scenario)["dt"]))
    assert hook(scenario, adapters.load("reference")) is None


def test_the_stiffness_case_sweeps_mujoco_solref_and_solimp_against_the_step() -> None:
    scenario = scenarios.build("slider_crank/stress_stiffness")
    hook = suites.get("stress").settings
    assert hook is not None
    mujoco = adapters.load("mujoco")
    settings = hook(scenario, mujoco) or []
    assert settings[0] == mujoco.default_setting(scenario)
    grid = {(s.mode, s["dt"], round(s["tc"] / s["dt"], 9), s["impedance"]) for s in settings[1:]}
    assert len(grid) == len(settings) - 1 == 2 * 6 * 3 * 3
