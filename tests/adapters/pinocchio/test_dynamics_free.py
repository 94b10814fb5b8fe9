"""Pinocchio in free dynamics: orders of its marching loops, energy drift, Andrews' squeezer.

Expected values are closed forms (the physical pendulum's small oscillation), the integrators'
promised orders, energy conservation, and the Test Set for IVP Solvers' published reference; the
native truth, which takes tens of seconds a scenario, is in test_dynamics_truth.py (slow).

Measured (2-core machine shared with other jobs):
    four_bar_gravity, default (baumgarte, dt = 1/8 output interval): energy drift 4.6e-8 J of a
    largest kinetic energy of 0.121 J (3.8e-7); compound_pendulum 2.4e-10 J of 4.5 J (5e-11)
    Andrews at t = 0.03 s, correct digits of beta theta gamma phi delta omega epsilon:
        default (baumgarte, dt = 1.25e-4)              5.35 5.25 4.77 5.64 7.37 5.65 6.71
        best of the ladder (baumgarte, dt = 1.5625e-5)  8.79 8.69 8.78 9.63 10.86 9.64 10.47
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

import scenarios
from adapters.base import Setting
from adapters.pinocchio import PinocchioAdapter
from scenarios.families.andrews_squeezer import ANGLES, REFERENCE
from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory


def run(scenario: Scenario, setting: Setting) -> Trajectory:
    result = PinocchioAdapter().run(scenario, setting)
    assert result.status == "ok", result.message
    trajectory = result.trajectory
    assert trajectory is not None and trajectory.position is not None and trajectory.velocity is not None
    return trajectory


def energy(scenario: Scenario, trajectory: Trajectory) -> tuple[np.ndarray, np.ndarray]:
    """(T + V, T) at every output time: T = sum 1/2 m v^2 + 1/2 J w^2, V = -sum m g . r."""
    gravity = np.asarray(scenario.gravity)
    assert trajectory.position is not None and trajectory.velocity is not None
    total = kinetic = np.zeros(len(trajectory.times))
    for body in scenario.bodies:
        k = trajectory.bodies.index(body.name)
        position, velocity = trajectory.position[:, k], trajectory.velocity[:, k]
        t = 0.5 * body.mass * (velocity[:, :2] ** 2).sum(axis=1) + 0.5 * body.inertia * velocity[:, 2] ** 2
        kinetic = kinetic + t
        total = total + t - body.mass * (position[:, :2] @ gravity)
    return total, kinetic


def test_the_physical_pendulum_oscillates_at_its_closed_form_frequency() -> None:
    """theta(t) = theta0 cos(sqrt(3 g / (2 l)) t) from the hanging position; theta0 = 1e-4 leaves a
    nonlinear term of theta0^3 / 16 ~ 6e-14 rad. Measured 6.9e-13 rad (RK4 at dt = 1.25e-3)."""
    scenario = scenarios.load("compound_pendulum/small_oscillation")
    trajectory = run(scenario, PinocchioAdapter().default_setting(scenario))
    assert trajectory.position is not None
    g, length = 9.81, scenario.body("link_1").length
    theta = 1e-4 * np.cos(math.sqrt(1.5 * g / length) * trajectory.times) - math.pi / 2
    assert np.abs(trajectory.position[:, 0, 2] - theta).max() < 3e-12


def differences(name: str, mode: str, per_period: tuple[int, ...], t_end: float) -> list[float]:
    """Largest position change between runs at successive steps per shortest period (Richardson's
    ratio of successive differences tends to 2^p for an order p method halving its step)."""
    scenario = scenarios.build(name, overrides={"t_end": t_end, "steps": 10})
    adapter = PinocchioAdapter()
    runs = [np.asarray(run(scenario, adapter.free_setting(scenario, mode, n)).position) for n in per_period]
    return [float(np.abs(a - b).max()) for a, b in itertools.pairwise(runs)]


@pytest.mark.parametrize(("mode", "order"), [("dynamic", 4), ("baumgarte", 4), ("euler", 1)])
def test_four_bar_gravity_converges_at_the_promised_order(mode: str, order: int) -> None:
    """RK4 (with or without the Baumgarte terms, whose gains stay fixed) is fourth order, semi-
    implicit Euler first order, over 0.3 s at 20 to 160 RK4 steps per shortest period (0.13 s),
    Euler at 80 to 640."""
    per_period = (20, 40, 80, 160) if mode != "euler" else (80, 160, 320, 640)
    found = differences("four_bar_gravity", mode, per_period, 0.3)
    orders = [math.log2(a / b) for a, b in itertools.pairwise(found)]
    assert all(abs(p - order) < 0.4 for p in orders), (found, orders)
    assert abs(orders[-1] - order) < 0.2, (found, orders)


@pytest.mark.parametrize(("name", "bound"), [("four_bar_gravity", 1e-6), ("compound_pendulum", 5e-10)])
def test_energy_drift_of_the_default_setting_is_bounded(name: str, bound: float) -> None:
    """Frictionless, so T + V is constant; drift relative to the largest kinetic energy (measured
    3.8e-7 on the four-bar, 5.4e-11 on the double pendulum)."""
    scenario = scenarios.load(name)
    total, kinetic = energy(scenario, run(scenario, PinocchioAdapter().default_setting(scenario)))
    drift = np.abs(total - total[0]).max() / kinetic.max()
    assert drift < bound, drift


def andrews_digits(setting: Setting | None = None) -> np.ndarray:
    scenario = scenarios.load("andrews_squeezer")
    trajectory = run(scenario, setting or PinocchioAdapter().default_setting(scenario))
    found = np.array([trajectory.extras[f"andrews.{a}"][-1] for a in ANGLES])
    reference = np.array(REFERENCE)
    return -np.log10(np.abs(found - reference) / np.abs(reference))  # type: ignore[no-any-return]


def test_andrews_default_setting_digits() -> None:
    """Measured 5.35 5.25 4.77 5.64 7.37 5.65 6.71 (the default: Baumgarte, 1.25e-4 s, 8 steps per
    output interval)."""
    digits = andrews_digits()
    assert np.all(digits > 4.3), dict(zip(ANGLES, digits.round(2), strict=True))
    assert np.median(digits) > 5.0


def test_andrews_best_setting_of_the_ladder_digits() -> None:
    """The finest Baumgarte setting of the ladder (10000 steps per shortest period), within about
    one digit of what the reference carries (about 10)."""
    scenario = scenarios.load("andrews_squeezer")
    adapter = PinocchioAdapter()
    best = adapter.free_setting(scenario, "baumgarte", 10000)
    assert best in adapter.ladder(scenario)
    digits = andrews_digits(best)
    assert np.all(digits > 8.2), dict(zip(ANGLES, digits.round(2), strict=True))


def test_without_baumgarte_the_n_four_bar_diverges_at_its_singular_position() -> None:
    """The stated reason the default is Baumgarte: without gains RK4 drifts off the loops of the
    IFToMM chain and diverges (measured at t = 1.25 s at the rule's step, 4.5e-4 s; at t = 3.1 s,
    its singular horizontal position, at 3.1e-3 s)."""
    scenario = scenarios.load("n_four_bar")
    adapter = PinocchioAdapter()
    plain = adapter.run(scenario, adapter.free_setting(scenario, "dynamic"))
    assert plain.status == "diverged" and plain.failure_time is not None and plain.failure_time > 0.5
    assert adapter.run(scenario, adapter.default_setting(scenario)).status == "ok"


def test_the_kinematic_mode_refuses_a_free_mechanism() -> None:
    result = PinocchioAdapter().run(scenarios.load("four_bar_gravity"), Setting.of("kinematic"))
    assert result.status == "failed" and "driven mechanisms" in result.message


def test_a_step_size_typed_by_mistake_is_refused_before_marching() -> None:
    scenario = scenarios.build("slider_crank", overrides={"steps": 4})
    result = PinocchioAdapter().run(scenario, Setting.of("euler", dt=1e-300))
    assert result.status == "failed" and "steps" in result.message
