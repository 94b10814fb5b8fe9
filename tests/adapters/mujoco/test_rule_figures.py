"""docs/settings-rule.md's MuJoCo sweeps recomputed: each figure of tests.support.rule_figures within
its TOLERANCE (the time constant on driven and free scenes, through singular passages, the direct
form beside the time-constant form, the faceted spline cam), against the harness truth."""

from __future__ import annotations

import functools

import numpy as np
import pytest

import scenarios
from adapters.base import Setting
from adapters.mujoco import MujocoAdapter
from adapters.mujoco.settings import DIRECT_FORM, own_regulariser
from reports.scoring.level_error import level_errors
from reports.scoring.truth import independent_truth
from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory
from tests.support import rule_figures as figures
from tests.support.bounds import held

ADAPTER = MujocoAdapter()
LEVELS = ("error_position", "error_velocity", "error_acceleration")
FIRST_SECOND = {"t_end": 1.0, "steps": 40}


@functools.cache
def scene(name: str, first_second: bool = False) -> Scenario:
    return scenarios.build(name, overrides=FIRST_SECOND if first_second else None)


@functools.cache
def truth(name: str, first_second: bool = False) -> Trajectory:
    scenario = scene(name, first_second)
    return independent_truth(scenario, np.asarray(scenario.times())).trajectory


def found(name: str, setting: Setting, first_second: bool = False) -> tuple[float, ...]:
    scenario = scene(name, first_second)
    result = ADAPTER.run(scenario, setting)
    assert result.status == "ok" and result.trajectory is not None, result.message
    errors = level_errors(scenario, result.trajectory, truth(name, first_second))
    return tuple(float(errors[level]) for level in LEVELS)


def default(name: str, first_second: bool = False) -> tuple[Setting, float]:
    setting = ADAPTER.default_setting(scene(name, first_second))
    return setting, float(setting["dt"])


def hold(values: tuple[float, ...], measured: tuple[float, ...]) -> None:
    held(values, measured, ("position", "velocity", "acceleration")[: len(values)], figures.TOLERANCE)


@pytest.mark.parametrize("steps", sorted(figures.MUJOCO_OWN_TC))
def test_own_regulariser_on_the_slider_crank(steps: float) -> None:
    setting, _ = default("slider_crank")
    hold(found("slider_crank", own_regulariser(setting, steps)), figures.MUJOCO_OWN_TC[steps])


@pytest.mark.parametrize(("name", "steps"), sorted(figures.MUJOCO_SCALED_TC))
def test_scaled_regulariser_time_constants(name: str, steps: float) -> None:
    setting, dt = default(name)
    hold(found(name, setting.replace(tc=steps * dt)), figures.MUJOCO_SCALED_TC[(name, steps)])


@pytest.mark.parametrize(("name", "steps"), sorted(figures.MUJOCO_FREE_TC))
def test_free_dynamics_time_constants(name: str, steps: float) -> None:
    setting, dt = default(name)
    hold(found(name, setting.replace(tc=steps * dt)), figures.MUJOCO_FREE_TC[(name, steps)])


@pytest.mark.parametrize("steps", [128.0, 1024.0])
def test_the_direct_form_gives_the_time_constant_form_s_errors(steps: float) -> None:
    setting, dt = default("four_bar_gravity")
    timed = found("four_bar_gravity", setting.replace(tc=steps * dt))
    direct = found("four_bar_gravity", setting.replace(tc=steps * dt, solref=DIRECT_FORM))
    np.testing.assert_allclose(direct, timed, rtol=1e-2)


@pytest.mark.parametrize("steps", sorted(figures.MUJOCO_SINGULAR_TC))
def test_through_singular_passages_a_shorter_time_constant_sags_less(steps: float) -> None:
    setting, dt = default("n_four_bar", first_second=True)
    hold(found("n_four_bar", setting.replace(tc=steps * dt), True), figures.MUJOCO_SINGULAR_TC[steps])


@pytest.mark.parametrize("weight", sorted(figures.MUJOCO_SINGULAR_WEIGHTS))
def test_a_smaller_regulariser_through_singular_passages(weight: float) -> None:
    setting, dt = default("n_four_bar", first_second=True)
    chosen = setting.replace(tc=1024.0 * dt, invweight=weight)
    hold(found("n_four_bar", chosen, True), figures.MUJOCO_SINGULAR_WEIGHTS[weight])


def test_the_smaller_regulariser_loses_four_bar_gravity() -> None:
    setting, _ = default("four_bar_gravity")
    hold(found("four_bar_gravity", setting.replace(invweight=1e-10))[:1], (figures.MUJOCO_OFF_BRANCH,))
    result = ADAPTER.run(scene("four_bar_gravity"), setting.replace(invweight=1e-12))
    assert result.status != "ok"


def test_the_1e_6_rung_lets_a_loop_near_its_singular_position_sag() -> None:
    setting, dt = default("n_four_bar", first_second=True)
    rung = setting.replace(invweight=1e-6, tc=128.0 * dt)
    assert scene("n_four_bar", True).characteristic_length == 1.0  # positions in m
    hold(found("n_four_bar", rung, True)[:1], (figures.MUJOCO_SINGULAR_SAG,))


@pytest.mark.parametrize(("pieces", "steps"), sorted(figures.MUJOCO_SPLINE_CAM))
def test_the_spline_cam_s_facets_and_contact_time_constant(pieces: int, steps: float) -> None:
    setting, dt = default("cam_roller/spline")
    chosen = setting.replace(cam_pieces=pieces, tc=steps * dt)
    hold(found("cam_roller/spline", chosen), figures.MUJOCO_SPLINE_CAM[(pieces, steps)])


@pytest.mark.parametrize(("pieces", "steps"), figures.MUJOCO_SPLINE_CAM_RINGING)
def test_the_spline_cam_rings_past_them(pieces: int, steps: float) -> None:
    setting, dt = default("cam_roller/spline")
    result = ADAPTER.run(scene("cam_roller/spline"), setting.replace(cam_pieces=pieces, tc=steps * dt))
    if result.status == "ok" and result.trajectory is not None:
        errors = level_errors(scene("cam_roller/spline"), result.trajectory, truth("cam_roller/spline"))
        assert errors["error_acceleration"] > figures.RINGING
