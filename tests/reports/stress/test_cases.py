"""The stress cases that probe an engine's own knobs (the constraint stiffness, the masses) ask each
engine for its settings (Adapter.probe_settings) and get exactly what the suite ran before the
engines owned them: the grids below are written out from the stress suite's declarations of
2026-11-25 (reports/stress/cases.py before the move), not read from the code under test."""

from __future__ import annotations

import itertools
import math

import pytest

import adapters
import scenarios
from adapters.base import Adapter, Setting
from reports.stress.cases import CASES, stress_settings
from tests.support.engines import ENGINES

STIFFNESS = "slider_crank/stress_stiffness"
MASS = ("four_bar", "four_bar/stress_mass_1e3", "four_bar/stress_mass_1e6")
KEEPS_DEFAULT = [e for e in ENGINES if adapters.adapter_class(e).probe_settings is Adapter.probe_settings]
"""The engines that declare no settings of their own for a probe (the base's answer)."""


def test_mujoco_sweeps_time_constant_and_impedance_against_the_step_on_the_stiffness_case() -> None:
    """RK4 and implicitfast, each at the scenario's output step and 2e-3 .. 3e-5 s, tc 2, 10 and
    50 steps, solimp 0.9, 0.99 and 0.9999, the default first."""
    scenario = scenarios.build(STIFFNESS)
    mujoco = adapters.load("mujoco")
    default = mujoco.default_setting(scenario)
    interval = scenario.t_end / scenario.steps
    expected = [default] + [
        Setting(mode, default.options).replace(dt=dt, tc=tc * dt, impedance=impedance)
        for mode, dt, tc, impedance in itertools.product(
            ("RK4", "implicitfast"),
            (interval, 2e-3, 1e-3, 3e-4, 1e-4, 3e-5),
            (2.0, 10.0, 50.0),
            (0.9, 0.99, 0.9999),
        )
    ]
    assert stress_settings(scenario, mujoco) == expected
    assert len(expected) == 1 + 2 * 6 * 3 * 3


def test_pinocchio_sweeps_baumgarte_gains_against_rk4_steps_on_the_stiffness_case() -> None:
    """Baumgarte at 100, 300 and 1000 RK4 steps per crank turn, rates g w for g = 1, 1e2, 1e3, 1e4
    (kp = (g w)^2, kd = 2 g w), after the kinematic default."""
    scenario = scenarios.build(STIFFNESS)
    pinocchio = adapters.load("pinocchio")
    w = abs(float(scenario.parameter("omega")))
    expected = [pinocchio.default_setting(scenario)] + [
        Setting.of("baumgarte", dt=2 * math.pi / w / n, kp=(g * w) ** 2, kd=2 * g * w)
        for n, g in itertools.product((100, 300, 1000), (1.0, 1e2, 1e3, 1e4))
    ]
    assert stress_settings(scenario, pinocchio) == expected


@pytest.mark.parametrize("name", MASS)
def test_the_mass_cases_run_mujoco_finer_and_pinocchio_dynamic(name: str) -> None:
    """MuJoCo at its default and a ten times finer step (tc follows the step); Pinocchio's dynamic
    mode (RK4, no gains) at 1000 steps per crank turn beside its kinematic default."""
    scenario = scenarios.build(name)
    mujoco, pinocchio = adapters.load("mujoco"), adapters.load("pinocchio")
    default = mujoco.default_setting(scenario)
    finer = float(default["dt"]) / 10
    chosen = stress_settings(scenario, mujoco)
    assert chosen is not None and chosen[0] == default and len(chosen) == 2
    assert chosen[1].mode == default.mode and chosen[1]["dt"] == finer
    assert math.isclose(chosen[1]["tc"] / finer, default["tc"] / default["dt"], rel_tol=1e-12)
    period = 2 * math.pi / abs(float(scenario.parameter("omega")))
    assert stress_settings(scenario, pinocchio) == [
        pinocchio.default_setting(scenario),
        Setting.of("dynamic", dt=period / 1000, kp=0.0, kd=0.0),
    ]


def test_mujoco_and_pinocchio_answer_for_themselves() -> None:
    assert {"mujoco", "pinocchio"}.isdisjoint(KEEPS_DEFAULT) and {"reference", "exudyn"} <= set(KEEPS_DEFAULT)


@pytest.mark.parametrize("engine", KEEPS_DEFAULT)
def test_an_engine_without_settings_for_a_probe_keeps_its_default(engine: str) -> None:
    adapter = adapters.load(engine)
    for name in (STIFFNESS, *MASS):
        assert stress_settings(scenarios.build(name), adapter) is None, name


def test_only_the_probe_cases_ask_the_engines() -> None:
    """Every other case with settings is engine-neutral (the speed cases' steps per revolution)."""
    probing = {name for name, case in CASES.items() if case.settings is not None and "speed" not in name}
    assert probing == {STIFFNESS, *MASS}
