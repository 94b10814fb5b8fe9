"""MuJoCo in free dynamics against the native truth (DOP853 on the augmented formulation).

What a careful MuJoCo model reaches, measured with the default (RK4 at the rule's step, solref time
constant 128 steps with the regulariser's invweight0 scaled by 1e-8, impedance 0.9999,
adapters.mujoco.weights): on open chains the integrator alone (the compound pendulum to 3e-12 m,
the stiff spring to 3e-10 m); on closed loops the `connect` equalities are held to 1e-8 in
accelerations (four_bar_gravity, Andrews' squeezer). With MuJoCo's own regulariser, the time
constant is held to a few steps and the accelerations carry RK4's error on the constraint mode
(about 1e-4 of their size) or the regulariser's sag; the bounds below are upper bounds from then.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import scenarios
from adapters.base import Setting
from adapters.mujoco.settings import DYNAMIC_TC_STEPS, INVWEIGHT, STEPS_PER_PERIOD, UNTUNED
from adapters.step_rule import shortest_period
from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory
from tests.support.mujoco.truths import ADAPTER, errors

SHORT = {"t_end": 0.25, "steps": 25}
"""A quarter second of the free four-bar and slider-crank: the default suite's horizon."""


def test_the_adapter_runs_dynamics_with_mujocos_integrators() -> None:
    scenario = scenarios.load("four_bar_gravity")
    assert ADAPTER.dynamics
    modes = {s.mode for s in ADAPTER.ladder(scenario)}
    assert modes == {"RK4", "implicit", "implicitfast", "Euler", UNTUNED}
    dt = shortest_period(scenario) / STEPS_PER_PERIOD
    expected = Setting.of("RK4", dt=dt, tc=DYNAMIC_TC_STEPS * dt, impedance=0.9999, invweight=INVWEIGHT)
    assert ADAPTER.default_setting(scenario) == expected


def test_the_start_velocity_is_the_bodies_rates() -> None:
    scenario = scenarios.load("compound_pendulum")
    omega = (1.5, -2.0)
    link_1, link_2 = scenario.bodies
    tip = np.array(link_1.guess[:2]) * 2.0  # link_1's far pin: its centre is midway from the origin
    v_1 = omega[0] * np.array([-link_1.guess[1], link_1.guess[0]])
    v_2 = omega[0] * np.array([-tip[1], tip[0]]) + omega[1] * np.array(
        [-(link_2.guess[1] - tip[1]), link_2.guess[0] - tip[0]]
    )
    rated = dataclasses.replace(
        scenario,
        bodies=(
            dataclasses.replace(link_1, rate=(*v_1, omega[0])),
            dataclasses.replace(link_2, rate=(*v_2, omega[1])),
        ),
    )
    result = ADAPTER.run(rated, times=[0.0])
    assert result.status == "ok", result.message
    assert result.trajectory is not None and result.trajectory.velocity is not None
    expected = np.array([[*v_1, omega[0]], [*v_2, omega[1]]])
    np.testing.assert_allclose(result.trajectory.velocity[0], expected, rtol=0, atol=1e-13)


@pytest.mark.parametrize(
    ("name", "overrides", "bounds"),
    [
        # measured 2.2e-8 / 3.8e-5 / 0.14
        ("four_bar_gravity", SHORT, (1e-7, 1e-4, 0.3)),
        # measured 8.4e-8 / 1.4e-5 / 0.12
        pytest.param("slider_crank_spring", SHORT, (2e-7, 3e-5, 0.3), marks=pytest.mark.slow),
        # two loops through the singular horizontal position; measured 1.0e-7 / 7.4e-7 / 8.3e-4
        ("n_four_bar", {"t_end": 1.0, "steps": 40}, (5e-7, 5e-6, 5e-3)),
        # open chain, no constraint: RK4 alone; measured 3e-12 / 4e-11 / 7e-10 (the truth's rtol)
        ("compound_pendulum", {"t_end": 1.0, "steps": 25}, (1e-10, 1e-9, 1e-8)),
    ],
)
def test_default_against_the_native_truth(
    name: str, overrides: dict[str, float], bounds: tuple[float, float, float]
) -> None:
    found = errors(name, None, **overrides)
    assert found["position"] < bounds[0], found
    assert found["velocity"] < bounds[1], found
    assert found["acceleration"] < bounds[2], found


@pytest.mark.slow
@pytest.mark.parametrize(
    ("name", "bounds"),
    [
        ("four_bar_gravity", (4e-7, 1e-4, 0.3)),  # measured 1.9e-7 / 4.0e-5 / 0.15
        ("slider_crank_spring", (2e-7, 3e-5, 0.3)),  # measured 8.5e-8 / 1.5e-5 / 0.12
        ("compound_pendulum", (1e-11, 1e-10, 2e-9)),  # measured 3.3e-12 / 2.7e-11 / 5.7e-10 (3e-4 s)
        ("stiff_spring", (1e-9, 1e-7, 2e-5)),  # measured 2.7e-10 / 4.3e-8 / 6.1e-6
        ("stiff_spring/damped", (1e-9, 1e-7, 2e-5)),  # measured 2.6e-10 / 4.1e-8 / 5.9e-6
        ("andrews_squeezer", (1e-3, 0.5, 1e3)),  # measured 3.9e-4 / 0.18 / 3.9e2
    ],
)
def test_default_against_the_native_truth_over_the_full_horizon(
    name: str, bounds: tuple[float, float, float]
) -> None:
    found = errors(name)
    assert found["position"] < bounds[0], found
    assert found["velocity"] < bounds[1], found
    assert found["acceleration"] < bounds[2], found


def energies(scenario: Scenario, trajectory: Trajectory) -> tuple[np.ndarray, np.ndarray]:
    """Kinetic and potential energy at every grid point from the trajectory's frame velocities
    (frames at the centres of mass) and heights."""
    assert trajectory.position is not None and trajectory.velocity is not None
    bodies = [scenario.body(name) for name in trajectory.bodies]
    mass = np.array([b.mass for b in bodies])
    inertia = np.array([b.inertia for b in bodies])
    v, r = trajectory.velocity, trajectory.position
    kinetic = 0.5 * (mass * (v[..., 0] ** 2 + v[..., 1] ** 2) + inertia * v[..., 2] ** 2).sum(axis=1)
    potential = -(mass * (r[..., :2] @ np.array(scenario.gravity))).sum(axis=1)
    return kinetic, potential


def energy_drift(name: str) -> float:
    """The default's largest change of T + V over the horizon, over the largest kinetic energy."""
    scenario = scenarios.load(name)
    result = ADAPTER.run(scenario)
    assert result.status == "ok", result.message
    assert result.trajectory is not None
    kinetic, potential = energies(scenario, result.trajectory)
    energy = kinetic + potential
    assert kinetic.max() > 0.01
    return float(np.abs(energy - energy[0]).max() / kinetic.max())


@pytest.mark.parametrize(
    ("name", "bound"),
    [
        ("four_bar_gravity", 5e-8),  # measured 1.2e-8 over 1 s
        ("compound_pendulum", 1e-12),  # measured 1.8e-13 over 2 s at 3e-4 s (no constraint to soften)
    ],
)
def test_energy_drift_of_the_default(name: str, bound: float) -> None:
    assert energy_drift(name) < bound
