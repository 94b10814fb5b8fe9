"""Energy drift of a dynamic run: its mechanical energy against the truth's, over time.

The mechanical energy E = T + V of a trajectory is computed here from its positions and velocities
alone, from the scenario's masses, inertias, gravity and springs, the same way for every engine and
for the truth (independently of the native solver's own energy accounting, which the tests check it
against):
    T = sum over bodies of 1/2 m (vx^2 + vy^2) + 1/2 J omega^2   (frames at the centres of mass)
    V = - sum m g . r  +  sum 1/2 k (l - l0)^2  +  sum 1/2 k (dtheta - theta0)^2
The drift at time t is the change of E since t0 minus the truth's change since t0, so in frictionless
scenes without applied loads (the truth's E constant) it is the run's own energy drift, and in
driven or damped ones it is its error in the energy balance. DRIFT_DEFINITION says how it is scaled.
"""

from __future__ import annotations

import math

import numpy as np

from scenarios.bodies import GROUND, Point
from scenarios.forces import RotationalSpringDamper, SpringDamper
from scenarios.geometry import world_point
from scenarios.scenario import Level, Scenario
from scenarios.trajectory import Trajectory

DRIFT_DEFINITION = (
    "energy drift = the largest |(E(t) - E(t0)) - (E_truth(t) - E_truth(t0))| over the grid, E = T + V "
    "computed from the run's positions and velocities, divided by the largest kinetic energy of the "
    "truth (at least sum m L^2 / t_end^2)"
)


def kinetic_energy(scenario: Scenario, trajectory: Trajectory) -> np.ndarray:
    """T at each grid time (needs velocities of every body)."""
    velocity = _level(trajectory, "velocity")
    out = np.zeros(len(trajectory.times))
    for body in scenario.bodies:
        v = velocity[:, trajectory.bodies.index(body.name), :]
        out += 0.5 * body.mass * (v[:, 0] ** 2 + v[:, 1] ** 2) + 0.5 * body.inertia * v[:, 2] ** 2
    return out


def potential_energy(scenario: Scenario, trajectory: Trajectory) -> np.ndarray:
    """V at each grid time: gravity about the global origin, and every spring's stored energy."""
    position = _level(trajectory, "position")
    g = np.asarray(scenario.gravity, dtype=float)
    out = np.zeros(len(trajectory.times))
    for body in scenario.bodies:
        r = position[:, trajectory.bodies.index(body.name), :2]
        out -= body.mass * (r @ g)
    for force in scenario.forces:
        if isinstance(force, SpringDamper):
            gap = _world(position, trajectory, force.p_j) - _world(position, trajectory, force.p_i)
            stretch = np.hypot(gap[:, 0], gap[:, 1]) - force.free_length
            out += 0.5 * force.stiffness * stretch**2
        elif isinstance(force, RotationalSpringDamper):
            turn = _angle(position, trajectory, force.body_j) - _angle(position, trajectory, force.body_i)
            out += 0.5 * force.stiffness * (turn - force.free_angle) ** 2
    return out


def mechanical_energy(scenario: Scenario, trajectory: Trajectory) -> np.ndarray:
    """E = T + V at each grid time."""
    return kinetic_energy(scenario, trajectory) + potential_energy(scenario, trajectory)


def energy_scale(scenario: Scenario, truth: Trajectory) -> float:
    """The largest kinetic energy of the truth, floored at sum m L^2 / t_end^2 (L the characteristic
    length) so that a scene nearly at rest is not judged against nothing."""
    span = float(truth.times[-1] - truth.times[0]) or 1.0
    mass = sum(body.mass for body in scenario.bodies)
    floor = mass * scenario.characteristic_length**2 / span**2
    return max(float(np.max(kinetic_energy(scenario, truth))), floor)


def drift_series(scenario: Scenario, result: Trajectory, truth: Trajectory) -> np.ndarray:
    """The scaled energy drift at each grid time (DRIFT_DEFINITION)."""
    mine, ref = mechanical_energy(scenario, result), mechanical_energy(scenario, truth)
    return np.abs((mine - mine[0]) - (ref - ref[0])) / energy_scale(scenario, truth)


def energy_drift(scenario: Scenario, result: Trajectory, truth: Trajectory) -> float:
    """The largest scaled drift over the grid where the truth is defined (NaN if nowhere)."""
    series = drift_series(scenario, result, truth)
    defined = series[np.isfinite(series)]
    return float(np.max(defined)) if defined.size else math.nan


def _level(trajectory: Trajectory, level: Level) -> np.ndarray:
    values = trajectory.level(level)
    if values is None:
        raise ValueError(f"the trajectory has no {level} level: no energy")
    return values


def _world(position: np.ndarray, trajectory: Trajectory, point: Point) -> np.ndarray:
    """A body point's world position at each grid time."""
    if point.body == GROUND:
        return np.broadcast_to(np.asarray(point.local, dtype=float), (len(trajectory.times), 2))
    poses = position[:, trajectory.bodies.index(point.body), :]
    return np.array([world_point((x, y, theta), point.local) for x, y, theta in poses])


def _angle(position: np.ndarray, trajectory: Trajectory, body: str) -> np.ndarray:
    if body == GROUND:
        return np.zeros(len(trajectory.times))
    return position[:, trajectory.bodies.index(body), 2]
