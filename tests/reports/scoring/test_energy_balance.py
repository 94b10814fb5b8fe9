"""The dynamic truth and the energy-drift metric against an independent energy balance, computed
here from the scenario's masses, inertias, gravity and forces and the trajectory alone:
    E(t) - E(0) = integral from 0 to t of P,   E = T + V,
T = sum 1/2 m |v|^2 + 1/2 J omega^2, V = -sum m g.r + sum 1/2 k (l - l0)^2 (+ torsion springs),
P the power of what is not in V: motor torques tau(t) (omega_body - omega_reaction), applied
forces F(t).v, and dampers -c l_dot^2 (torsion: -c (omega_j - omega_i)^2), integrated by Simpson's
rule on a fine grid. Nothing here comes from reports.scoring.energy_drift or the solver's own energy
accounting (the metric's other check, test_energy_drift.py)."""

from __future__ import annotations

import functools

import numpy as np
import pytest
from scipy.integrate import cumulative_simpson

from reference_solver.dynamics import simulate
from reports.scoring.energy_drift import energy_drift
from reports.scoring.truth import NATIVE_DYNAMIC, independent_truth
from scenarios import Scenario, Trajectory, load
from scenarios.bodies import GROUND, Point
from scenarios.forces import AppliedForce, AppliedTorque, RotationalSpringDamper, SpringDamper


def state(scenario: Scenario, trajectory: Trajectory, body: str) -> tuple[np.ndarray, np.ndarray]:
    """A body's (x, y, theta) and (vx, vy, omega) at each time; zeros for the ground."""
    if body == GROUND:
        zero = np.zeros((len(trajectory.times), 3))
        return zero, zero
    k = trajectory.bodies.index(body)
    return trajectory.position[:, k], trajectory.velocity[:, k]  # type: ignore[index]


def point(scenario: Scenario, trajectory: Trajectory, at: Point) -> tuple[np.ndarray, np.ndarray]:
    """A body point's world position and velocity: r = R(theta) local, v = v_body + omega x r."""
    q, v = state(scenario, trajectory, at.body)
    c, s = np.cos(q[:, 2]), np.sin(q[:, 2])
    rx, ry = at.local[0] * c - at.local[1] * s, at.local[0] * s + at.local[1] * c
    return q[:, :2] + np.column_stack([rx, ry]), v[:, :2] + v[:, 2:3] * np.column_stack([-ry, rx])


def energy(scenario: Scenario, trajectory: Trajectory) -> tuple[np.ndarray, np.ndarray]:
    """(T, V) at each time."""
    g = np.asarray(scenario.gravity)
    kinetic, potential = np.zeros(len(trajectory.times)), np.zeros(len(trajectory.times))
    for body in scenario.bodies:
        q, v = state(scenario, trajectory, body.name)
        kinetic += 0.5 * body.mass * (v[:, 0] ** 2 + v[:, 1] ** 2) + 0.5 * body.inertia * v[:, 2] ** 2
        potential -= body.mass * (q[:, :2] @ g)
    for force in scenario.forces:
        if isinstance(force, SpringDamper):
            (pi, _), (pj, _) = point(scenario, trajectory, force.p_i), point(scenario, trajectory, force.p_j)
            potential += 0.5 * force.stiffness * (np.linalg.norm(pj - pi, axis=1) - force.free_length) ** 2
        elif isinstance(force, RotationalSpringDamper):
            turn = (
                state(scenario, trajectory, force.body_j)[0][:, 2]
                - state(scenario, trajectory, force.body_i)[0][:, 2]
            )
            potential += 0.5 * force.stiffness * (turn - force.free_angle) ** 2
    return kinetic, potential


def power(scenario: Scenario, trajectory: Trajectory) -> np.ndarray:
    """The power of the motors, applied forces and dampers at each time."""
    t, out = trajectory.times, np.zeros(len(trajectory.times))
    for force in scenario.forces:
        if isinstance(force, AppliedTorque):
            tau = np.array([force.torque.f(float(s)) for s in t])
            rate = (
                state(scenario, trajectory, force.body)[1][:, 2]
                - state(scenario, trajectory, force.reaction)[1][:, 2]
            )
            out += tau * rate
        elif isinstance(force, AppliedForce):
            load_ = np.column_stack([[force.fx.f(float(s)) for s in t], [force.fy.f(float(s)) for s in t]])
            out += np.sum(load_ * point(scenario, trajectory, force.point)[1], axis=1)
        elif isinstance(force, SpringDamper):
            (pi, vi), (pj, vj) = (
                point(scenario, trajectory, force.p_i),
                point(scenario, trajectory, force.p_j),
            )
            gap = pj - pi
            stretch_rate = np.sum(gap * (vj - vi), axis=1) / np.linalg.norm(gap, axis=1)
            out -= force.damping * stretch_rate**2
        elif isinstance(force, RotationalSpringDamper):
            rate = (
                state(scenario, trajectory, force.body_j)[1][:, 2]
                - state(scenario, trajectory, force.body_i)[1][:, 2]
            )
            out -= force.damping * rate**2
    return out


def work(scenario: Scenario, trajectory: Trajectory) -> np.ndarray:
    """The work done on the system since t0 (Simpson's rule on the trajectory's grid)."""
    return cumulative_simpson(power(scenario, trajectory), x=trajectory.times, initial=0.0)


SCENES = {
    # name: (grid overrides: fine enough for Simpson's rule, the truth's balance residual over the
    # energy scale as measured, the loose tolerance of the run that drifts)
    "compound_pendulum": ({"steps": 1000}, 3.7e-13, 1e-6),
    # the slower ones (the tight truth takes 3 to 9 s each): CI runs them
    "four_bar_gravity": ({"steps": 1000}, 2.3e-12, 1e-8),  # at rtol 1e-6 the native run stops at 0.41 s
    # damper and motor; Simpson's error: 1.0e-7, 6.5e-9, 4.1e-10 at 1000, 2000, 4000 steps (order 4)
    "slider_crank_spring": ({"steps": 4000}, 4.1e-10, 1e-6),
    # motor and spring on seven bodies; Simpson's error again: 1.5e-8 at 600 steps, 2.4e-11 at 3000
    "andrews_squeezer": ({"steps": 3000}, 2.4e-11, 1e-6),
    # a stiff damper; the same at 8000 steps: the truth's own residual, not the quadrature's
    "stiff_spring/damped": ({"steps": 4000}, 3.3e-12, 1e-6),
}
SLOW = {name: pytest.param(name, marks=pytest.mark.slow) for name in list(SCENES)[1:]}
CASES = ["compound_pendulum", *SLOW.values()]


@functools.cache
def truth(name: str) -> tuple[Scenario, Trajectory]:
    scenario = load(name, {k: str(v) for k, v in SCENES[name][0].items()})
    named = independent_truth(scenario, np.asarray(scenario.times()))
    assert named.name == NATIVE_DYNAMIC
    return scenario, named.trajectory


def balance(scenario: Scenario, trajectory: Trajectory, against: Trajectory) -> np.ndarray:
    """E(t) - E(0) of `trajectory` minus the work done on `against` since t0."""
    kinetic, potential = energy(scenario, trajectory)
    total = kinetic + potential
    return total - total[0] - work(scenario, against)


def scale(scenario: Scenario, trajectory: Trajectory) -> float:
    """The drift's scale as the metric defines it (DRIFT_DEFINITION): the truth's largest kinetic
    energy, at least sum m L^2 / t_end^2."""
    span = float(trajectory.times[-1] - trajectory.times[0])
    floor = sum(body.mass for body in scenario.bodies) * scenario.characteristic_length**2 / span**2
    return max(float(np.max(energy(scenario, trajectory)[0])), floor)


@pytest.mark.parametrize("name", CASES)
def test_the_dynamic_truth_keeps_the_energy_balance(name: str) -> None:
    scenario, reference = truth(name)
    residual = np.max(np.abs(balance(scenario, reference, reference))) / scale(scenario, reference)
    print(name, "energy balance residual / energy scale:", residual)
    assert residual <= 3 * SCENES[name][1]  # the dynamic truth is at DOP853 rtol 1e-13


@pytest.mark.parametrize("name", CASES)
def test_the_energy_drift_metric_meets_the_independent_balance(name: str) -> None:
    """A native run at a loose rtol drifts; the metric's drift equals the independent one,
    |(E_run(t) - E_run(0)) - W_truth(t)| / max T, to within the truth's own balance residual."""
    scenario, reference = truth(name)
    run = simulate(scenario, reference.times, SCENES[name][2]).trajectory()
    size = scale(scenario, reference)
    independent = np.max(np.abs(balance(scenario, run, reference))) / size
    residual = np.max(np.abs(balance(scenario, reference, reference))) / size
    metric = energy_drift(scenario, run, reference)
    print(name, "drift: metric", metric, "independent", independent, "truth's residual", residual)
    assert independent > 10 * residual  # the run's drift stands out from the truth's balance
    assert abs(metric - independent) <= residual + 1e-12 * independent
