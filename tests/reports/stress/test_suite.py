"""The stress suite: every stress variant declared, its truth, its settings hook, and the native
solver's accuracy across the scale and speed extremes against closed forms."""

from __future__ import annotations

import numpy as np
import pytest

import adapters
import scenarios
from reference_solver import solve
from reports.harness import suites
from reports.stress.cases import CASES, NOMINAL_SPEED
from reports.stress.truth import partial_truth, stress_truth
from scenarios.closed_form import exact
from scenarios.scenario import LEVELS
from scenarios.trajectory import Trajectory


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
    assert suite.truth is not None and suite.settings is not None and not suite.sweep


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


def test_a_refined_truth_follows_the_branch_the_coarse_grid_loses() -> None:
    """Near the change point the truth solved on a 4x grid is finite to the end and agrees with a
    16x grid at the scenario's times."""
    scenario = scenarios.build("four_bar/stress_near_change_point")
    times = np.asarray(scenario.times())
    truth = stress_truth(scenario, times)
    finer = partial_truth(scenario, times, refine=16)
    assert np.all(np.isfinite(positions(truth)))
    assert np.max(np.abs(positions(truth) - positions(finer))) < 1e-12


@pytest.mark.parametrize("name", ["slider_crank/stress_scale_1e-4", "slider_crank/stress_speed_1e-3"])
def test_a_similar_case_takes_the_mapped_nominal_truth(name: str) -> None:
    """The nominal truth, lengths and time mapped, equals the case solved directly."""
    scenario = scenarios.build(name)
    times = np.asarray(scenario.times())
    mapped, direct = stress_truth(scenario, times), solve(scenario, times)
    length = scenario.characteristic_length
    omega = abs(float(scenario.parameter("omega")))
    for level, scale in (("position", 1.0), ("velocity", omega), ("acceleration", omega**2)):
        diff = np.abs(mapped.level(level) - direct.level(level))  # type: ignore[arg-type,operator]
        assert diff[..., :2].max() / (length * scale) < 1e-12, level
        assert diff[..., 2].max() / scale < 1e-12, level


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
