"""An ok run that drifted says so by its own figures, with no truth: hand-made verdicts, the scenes
whose T + V must stay constant, a doctored trajectory caught, a gross drift warned about by `solve`,
and no alarm on the engines' default runs (measured margins: energy changes at most 5.2e-6 against
the 1e-2 limit, residuals at most 8.9e-10 against 1e-3, over the dynamics suite's default runs)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import scenarios
from adapters import load as load_engine
from reference_solver.dynamics import simulate
from reports.cli.main import main
from reports.harness import self_check
from scenarios.trajectory import Trajectory
from tests.support.engines import ENGINES


def test_the_verdict_names_what_drifted_and_its_limit() -> None:
    assert self_check.verdict(1e-9, 1e-6) == ""
    assert self_check.verdict(math.nan, math.nan) == ""  # not measured is no alarm
    assert self_check.verdict(2e-3, math.nan) == "drifted: constraint residual 0.002 (limit 0.001)"
    both = self_check.verdict(2e-3, 0.5)
    assert both.startswith("drifted: constraint residual") and "T + V changed by 0.5" in both
    assert "not finite" in self_check.verdict(math.inf, math.nan)


@pytest.mark.parametrize(
    ("name", "conservative"),
    [
        ("four_bar_gravity", True),
        ("compound_pendulum", True),
        ("stiff_spring", True),
        ("stiff_spring/damped", False),
        ("andrews_squeezer", False),
        ("four_bar", False),
    ],
)
def test_which_scenes_keep_t_plus_v(name: str, conservative: bool) -> None:
    assert self_check.conservative(scenarios.build(name)) is conservative


def test_the_native_truth_keeps_its_energy_and_a_doctored_one_does_not() -> None:
    scenario = dataclasses.replace(scenarios.build("compound_pendulum"), t_end=0.5, steps=25)
    truth = simulate(scenario, np.asarray(scenario.times()), 1e-12).trajectory()
    assert self_check.energy_change(scenario, truth) < 1e-9
    assert truth.velocity is not None
    doctored = Trajectory(
        truth.times,
        truth.bodies,
        truth.position,
        truth.velocity * np.linspace(1, 1.2, 26)[:, None, None],
        truth.acceleration,
    )
    change = self_check.energy_change(scenario, doctored)
    assert change > self_check.ENERGY_LIMIT
    assert "T + V changed" in self_check.verdict(0.0, change)


def test_solve_warns_on_a_gross_drift_and_keeps_exit_0(capsys, tmp_path) -> None:
    argv = [
        "solve",
        "four_bar_gravity",
        "--engine",
        "mujoco",
        "--mode",
        "Euler",
        "--setting",
        "dt=0.00215818",
    ]
    assert main([*argv, "--out", str(tmp_path / "x.csv")]) == 0
    err = capsys.readouterr().err
    assert err.startswith("mbxval: warning: mujoco drifted: constraint residual") and err.count("\n") == 1


@pytest.mark.parametrize("engine", ENGINES)
def test_no_alarm_on_a_default_run(engine: str) -> None:
    scenario = scenarios.build("four_bar_gravity")
    adapter = load_engine(engine)
    if adapter.supports(scenario) is not None or not adapter.dynamics:
        pytest.skip(f"{engine} does not run {scenario.name}")
    result = adapter.run(scenario, adapter.default_setting(scenario), np.asarray(scenario.times()))
    assert result.status == "ok" and result.trajectory is not None
    assert self_check.of_trajectory(scenario, result.trajectory) == ""
    assert self_check.energy_change(scenario, result.trajectory) < self_check.ENERGY_LIMIT / 1000


@pytest.mark.parametrize(
    ("residual", "energy", "drifted"),
    [
        (0.99e-3, math.nan, False),
        (1.01e-3, math.nan, True),
        (0.0, 0.99e-2, False),
        (0.0, 1.01e-2, True),
    ],
)
def test_each_limit_is_pinned_by_a_case_just_inside_and_just_outside(
    residual: float, energy: float, drifted: bool
) -> None:
    """The documented limits (README: residual 1e-3, energy 1e-2), written here as numbers so that a
    changed limit is caught."""
    assert bool(self_check.verdict(residual, energy)) is drifted
