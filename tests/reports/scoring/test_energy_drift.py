"""The harness's energy of a trajectory against the native solver's own energy accounting (two
independent computations), and the drift metric on trajectories of known drift."""

from __future__ import annotations

import dataclasses
import functools

import numpy as np
import pytest

from reference_solver.dynamics import simulate
from reports.scoring.energy_drift import (
    energy_drift,
    energy_scale,
    kinetic_energy,
    potential_energy,
)
from scenarios import Scenario, Trajectory, load
from scenarios.bodies import GROUND, Point
from scenarios.forces import RotationalSpringDamper, SpringDamper

SCENES = ["four_bar_gravity", "compound_pendulum", "slider_crank_spring", "stiff_spring/damped"]


@functools.cache
def _native(name: str) -> tuple[Scenario, Trajectory]:
    """A short run: the energies are compared on the same trajectory, so its accuracy is moot."""
    scenario = load(name, {"t_end": 0.2, "steps": 10} if name != "stiff_spring/damped" else {"t_end": 0.01})
    return scenario, simulate(scenario, np.asarray(scenario.times()), 1e-6).trajectory()


@pytest.mark.parametrize("name", SCENES)
def test_energy_matches_the_native_accounting(name: str) -> None:
    scenario, trajectory = _native(name)
    scale = energy_scale(scenario, trajectory)
    kinetic = kinetic_energy(scenario, trajectory)
    potential = potential_energy(scenario, trajectory)
    assert np.max(np.abs(kinetic - trajectory.extras["energy.kinetic"])) < 1e-12 * scale
    assert np.max(np.abs(potential - trajectory.extras["energy.potential"])) < 1e-12 * scale


def test_the_truth_has_no_drift_against_itself() -> None:
    scenario, trajectory = _native("four_bar_gravity")
    assert energy_drift(scenario, trajectory, trajectory) == 0.0


def test_a_known_energy_error_is_measured() -> None:
    """Velocities scaled by (1 + e) from the second grid time on add e (2 + e) T(t) to the energy:
    the drift is that over the largest kinetic energy."""
    scenario, truth = _native("four_bar_gravity")
    e = 1e-3
    velocity = truth.velocity.copy()
    velocity[1:] *= 1.0 + e
    run = dataclasses.replace(truth, velocity=velocity)
    kinetic = kinetic_energy(scenario, truth)
    expected = np.max(e * (2 + e) * kinetic[1:]) / np.max(kinetic)
    assert energy_drift(scenario, run, truth) == pytest.approx(expected, rel=1e-9)


def test_a_trajectory_without_velocities_is_refused() -> None:
    scenario, truth = _native("four_bar_gravity")
    with pytest.raises(ValueError, match="no velocity"):
        energy_drift(scenario, dataclasses.replace(truth, velocity=None), truth)


def _sprung_four_bar() -> tuple[Scenario, Trajectory]:
    """The four-bar under gravity with a torsion spring between coupler and rocker (both moving, so
    both angles enter, with a free angle), another from the ground to the crank, and a spring
    between points of the crank and the rocker: each term of V has bodies on both ends."""
    scenario = load("four_bar_gravity", {"t_end": 0.2, "steps": 10})
    forces = (
        RotationalSpringDamper("twist", "coupler", "rocker", stiffness=3.0, free_angle=0.2),
        RotationalSpringDamper("wind", GROUND, "crank", stiffness=0.5, free_angle=-0.1),
        SpringDamper("tie", Point("crank", (0.01, 0.0)), Point("rocker", (0.02, 0.01)), 40.0, 0.0, 0.05),
    )
    scenario = dataclasses.replace(scenario, forces=forces)
    return scenario, simulate(scenario, np.asarray(scenario.times()), 1e-6).trajectory()


def test_springs_between_moving_bodies_store_the_native_accounting_s_energy() -> None:
    scenario, trajectory = _sprung_four_bar()
    scale = energy_scale(scenario, trajectory)
    potential = potential_energy(scenario, trajectory)
    assert np.ptp(potential) > 1e-3 * scale  # the springs work over the run
    assert np.max(np.abs(potential - trajectory.extras["energy.potential"])) < 1e-12 * scale


def test_a_truth_defined_nowhere_gives_no_drift() -> None:
    """A truth whose velocities are NaN throughout (undefined at every time) has no drift: NaN."""
    scenario, truth = _native("four_bar_gravity")
    undefined = dataclasses.replace(truth, velocity=np.full_like(truth.velocity, np.nan))
    assert np.isnan(energy_drift(scenario, truth, undefined))


def _at_rest(times: np.ndarray) -> tuple[Scenario, Trajectory]:
    """The four-bar with gravity held still at its first pose on the grid `times`: no kinetic
    energy, so the scale is the floor alone."""
    scenario, truth = _native("four_bar_gravity")
    pose = np.repeat(truth.position[:1], times.size, axis=0)
    rest = np.zeros_like(pose)
    return scenario, Trajectory(times, truth.bodies, pose, rest, rest)


def test_a_scene_at_rest_is_scaled_by_the_mass_times_the_length_squared_over_the_span_squared() -> None:
    """sum m L^2 / (t_end - t_0)^2 on a grid from t = 1 to 4 (span 3, L = 0.05 m: neither 1 nor
    2, so a wrong power of either shows), and over a span of 1 for a single grid time."""
    scenario, still = _at_rest(np.linspace(1.0, 4.0, 7))
    mass = sum(body.mass for body in scenario.bodies)
    length = scenario.characteristic_length
    assert length not in (1.0, 2.0) and mass > 0.0
    assert energy_scale(scenario, still) == pytest.approx(mass * length**2 / 9.0, rel=1e-15)
    _, instant = _at_rest(np.array([2.5]))
    assert energy_scale(scenario, instant) == pytest.approx(mass * length**2, rel=1e-15)
