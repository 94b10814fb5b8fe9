"""Exudyn in free dynamics against the native truth (reference_solver.dynamics, DOP853 at a tight
tolerance, independent of Exudyn): every dynamic scenario at the default setting (generalized-alpha,
spectral radius 0.9, ten steps per output interval), the force elements no catalogue scenario has
yet, and the modes Exudyn cannot run. Bounds are about twice what the model measured (noted per
case): a careful generalized-alpha model at that step reaches them, a wrong force or sign does not."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from adapters.base import Setting
from scenarios.bodies import GROUND, Point
from scenarios.forces import AppliedForce, AppliedTorque, RotationalSpringDamper, SpringDamper
from scenarios.motions import Constant, Harmonic
from tests.support.exudyn.dynamics import ADAPTER, position_error, run, scenario, truth

# (scenario, shortened horizon, bound); measured position errors at the default setting:
# 9.5e-7, 3.5e-6, 4.5e-10, 4.7e-5, 5.3e-5, 3.2e-5, 4.9e-9, 4.9e-9, 1.7e-6
SHORT = [
    ("four_bar_gravity", {"t_end": 0.1, "steps": 20}, 2e-6),
    ("compound_pendulum", {"t_end": 0.2, "steps": 20}, 7e-6),
    ("compound_pendulum/small_oscillation", {"t_end": 0.5, "steps": 50}, 1e-9),
    ("slider_crank_spring", {"t_end": 0.05, "steps": 10}, 1e-4),
    ("slider_crank_spring/undamped", {"t_end": 0.05, "steps": 10}, 1e-4),
    ("andrews_squeezer", {"t_end": 0.003, "steps": 3}, 7e-5),
    ("stiff_spring", {"t_end": 0.005}, 1e-8),
    ("stiff_spring/damped", {"t_end": 0.005}, 1e-8),
    ("n_four_bar", {"t_end": 0.25, "steps": 10}, 4e-6),
]

# full horizons; measured: 9.8e-4, 6.6e-5, 2.7e-9, 1.4e-4, 0.11, 8.6e-3, 2.6e-8, 2.5e-8, 4.3e-4
# (the undamped slider-crank spins up under its torque: 0.11 of a crank length at the default,
# second order in the step like the rest)
FULL = [
    ("four_bar_gravity", 2e-3),
    ("compound_pendulum", 1.5e-4),
    ("compound_pendulum/small_oscillation", 6e-9),
    ("slider_crank_spring", 3e-4),
    ("slider_crank_spring/undamped", 0.25),
    ("andrews_squeezer", 2e-2),
    ("stiff_spring", 6e-8),
    ("stiff_spring/damped", 6e-8),
    ("n_four_bar", 1e-3),
]


@pytest.mark.parametrize(("name", "overrides", "bound"), SHORT, ids=[case[0] for case in SHORT])
def test_the_default_follows_the_native_truth(name: str, overrides: dict[str, float], bound: float) -> None:
    s = scenario(name, **overrides)
    assert position_error(s, run(s), truth(s, 1e-11)) < bound


@pytest.mark.slow
@pytest.mark.parametrize(("name", "bound"), FULL, ids=[case[0] for case in FULL])
def test_the_default_follows_the_native_truth_over_the_whole_horizon(name: str, bound: float) -> None:
    s = scenario(name)
    assert position_error(s, run(s), truth(s, 1e-12)) < bound


def test_the_initial_accelerations_are_the_constrained_dynamics() -> None:
    """Exudyn's own initial accelerations (computed at build) match the truth's at t = 0."""
    s = scenario("four_bar_gravity", t_end=0.005, steps=1)
    mine, ref = run(s), truth(s)
    assert mine.acceleration is not None and ref.acceleration is not None
    np.testing.assert_allclose(mine.acceleration[0], ref.acceleration[0], rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(mine.position[0], ref.position[0], rtol=0, atol=1e-15)  # type: ignore[index]


def test_every_force_element_with_its_sign() -> None:
    """Torques with a reaction body, a time-varying force at a body point, rotational springs to
    the ground and between bodies, a damped spring: each as an Exudyn element, against the truth.
    Measured 2.0e-5 and 1.8e-6 at a thirtieth and a hundredth of the output interval (second order
    down to 2e-7: no modelling bias left); leaving out any one element is off by 0.03 or more."""
    base = scenario("compound_pendulum", t_end=0.2, steps=20)
    forces = (
        AppliedTorque("motor", "link_2", Harmonic(0.0, 3.0, 20.0), reaction="link_1"),
        AppliedTorque("brake", "link_1", Constant(-1.5)),
        AppliedForce("push", Point("link_2", (0.2, 0.05)), Harmonic(1.0, 4.0, 15.0, 0.3), Constant(-2.0)),
        RotationalSpringDamper("hip", GROUND, "link_1", 40.0, 0.5, -1.2),
        RotationalSpringDamper("knee", "link_1", "link_2", 25.0, 0.2, 0.4),
        SpringDamper("strut", Point("link_2", (0.1, 0.0)), Point(GROUND, (0.5, 0.3)), 300.0, 2.0, 0.6),
    )
    s = replace(base, forces=forces)
    interval = float(s.t_end / s.steps)
    ref = truth(s)
    coarse = position_error(s, run(s, Setting.of("GA3", dt=interval / 30)), ref)
    fine = position_error(s, run(s, Setting.of("GA3", dt=interval / 100)), ref)
    assert fine < 4e-6
    assert coarse / fine > 8.0  # (100 / 30)^2 = 11
    without_knee = replace(s, forces=forces[:-2] + forces[-1:])
    assert position_error(s, run(without_knee, Setting.of("GA3", dt=interval / 100)), ref) > 1e-2


@pytest.mark.parametrize("mode", ["RK44"])
def test_explicit_integrators_are_unsupported_on_jointed_scenes(mode: str) -> None:
    result = ADAPTER.run(scenario("four_bar_gravity"), Setting.of(mode, dt=1e-3))
    assert result.status == "unsupported"
    assert "explicit" in result.message and "Revolute" in result.message


def test_the_static_solver_is_not_offered_for_free_dynamics() -> None:
    s = scenario("compound_pendulum")
    assert ADAPTER.run(s, Setting.of("STATIC")).status == "unsupported"
    assert {setting.mode for setting in ADAPTER.ladder(s)} == {"GA3", "GA3-rho0.5", "GA3-modified", "TR2"}


def test_an_uneven_grid_is_interpolated_and_the_row_says_so() -> None:
    """Outputs of an even grid fall on Exudyn's steps; an uneven grid's between steps are
    interpolated on the rule's march, and the run's warnings say so."""
    free = scenario("four_bar_gravity")
    uneven = ADAPTER.run(free, times=np.array([0.0, 0.01, 0.03]))
    even = ADAPTER.run(free, times=np.linspace(0.0, 0.03, 4))
    assert uneven.status == even.status == "ok", (uneven.message, even.message)
    assert any("interpolated" in w for w in uneven.warnings), uneven.warnings
    assert not any("interpolated" in w for w in even.warnings), even.warnings
