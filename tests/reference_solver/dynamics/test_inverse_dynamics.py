"""Inverse dynamics of the driven kinematic families: the driver's torque or force from lambda
against virtual work. With no load but the driver, its power equals the rate of change of kinetic
energy, dT/dt = sum(m v . a + J omega alpha), computed from the kinematic analysis alone."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

import scenarios
from reference_solver import analyse
from reference_solver.dynamics import inverse_dynamics
from scenarios import GROUND
from scenarios.drivers import AbsoluteDriver
from scenarios.forces import AppliedTorque, RotationalSpringDamper


def kinetic_rate(scenario: scenarios.Scenario, qd: np.ndarray, qdd: np.ndarray) -> np.ndarray:
    m = np.concatenate([[b.mass, b.mass, b.inertia] for b in scenario.bodies])
    return np.sum(m * qd * qdd, axis=1)  # type: ignore[no-any-return]


@pytest.mark.parametrize(
    "name", ["four_bar", "slider_crank", "slider_crank/offset", "slider_crank/slider_drive", "four_bar_chain"]
)
def test_driver_power_equals_the_rate_of_kinetic_energy(name: str) -> None:
    scenario = scenarios.build(name, overrides={"steps": 60})
    analysis = analyse(scenario)
    extras = inverse_dynamics(scenario, analysis)
    (driver,) = scenario.drivers
    assert isinstance(driver, AbsoluteDriver)
    column = analysis.layout.body_column(driver.body)
    assert column is not None
    rate = analysis.qd[:, column + {"x": 0, "y": 1, "theta": 2}[driver.coordinate]]
    power = extras[f"{driver.name}.force"] * rate
    expected = kinetic_rate(scenario, analysis.qd, analysis.qdd)
    scale = np.max(np.abs(expected))
    assert scale > 0
    np.testing.assert_allclose(power, expected, rtol=0, atol=1e-9 * scale)


def test_a_driver_holding_a_pendulum_carries_its_static_gravity_torque() -> None:
    """A rod pinned at one end, held horizontal by a driver: the driver's torque is m g l / 2."""
    rod = scenarios.build("compound_pendulum", overrides={"links": 1, "theta0": math.pi / 2})
    hold = AbsoluteDriver("hold", "link_1", "theta", scenarios.Constant(0.0))
    held = replace(rod, drivers=(hold,), analysis="kinematic")
    extras = inverse_dynamics(held, analyse(held, [0.0, 0.1]))
    np.testing.assert_allclose(extras["hold.force"], 1.0 * 9.81 * 0.5 / 2, rtol=1e-12)
    # The pin carries the rod's weight: the force it applies to the rod is straight up.
    np.testing.assert_allclose(extras["pin_1.fy"], 9.81, rtol=1e-12)
    np.testing.assert_allclose(extras["pin_1.fx"], 0.0, atol=1e-12)


def test_a_rod_turned_at_constant_speed_about_its_end_carries_gravity_s_moment_and_its_energies() -> None:
    """A uniform rod (m = 1 kg, l = 0.5 m, J = m l^2 / 12 about its centre) pinned at one end and
    driven at theta = 0.3 + 2 t against a torsion damper to the ground (c = 0.7) and a torque
    0.4 cos(3 t): no angular acceleration, so the driver's torque is the weight's moment about the
    pin, m g l/2 cos(theta), plus c omega, minus the applied torque; T = (J + m l^2/4) omega^2 / 2
    and V = m g l/2 sin(theta)."""
    rod = scenarios.build("compound_pendulum", overrides={"links": 1})
    turn = AbsoluteDriver("turn", "link_1", "theta", scenarios.ConstantSpeed(0.3, 2.0))
    loads = (
        RotationalSpringDamper("damper", GROUND, "link_1", 0.0, 0.7),
        AppliedTorque("motor", "link_1", scenarios.Harmonic(0.0, 0.4, 3.0)),
    )
    driven = replace(rod, drivers=(turn,), forces=loads, analysis="kinematic")
    times = np.linspace(0.0, 1.0, 6)
    extras = inverse_dynamics(driven, analyse(driven, times))
    theta, m, g, half = 0.3 + 2.0 * times, 1.0, 9.81, 0.25
    torque = m * g * half * np.cos(theta) + 0.7 * 2.0 - 0.4 * np.cos(3.0 * times)
    np.testing.assert_allclose(extras["turn.force"], torque, rtol=0, atol=1e-12)
    alone = inverse_dynamics(driven, analyse(driven, times[:1]))  # one time: one row
    assert {key: value.shape for key, value in alone.items()} == dict.fromkeys(extras, (1,))
    np.testing.assert_allclose(alone["turn.force"], torque[:1], rtol=0, atol=1e-12)
    np.testing.assert_allclose(
        extras["energy.kinetic"], (m * 0.5**2 / 12 + m * half**2) * 2.0**2 / 2, rtol=1e-12
    )
    np.testing.assert_allclose(extras["energy.potential"], m * g * half * np.sin(theta), rtol=0, atol=1e-12)


def test_a_cam_follower_s_driver_power_is_the_rate_of_kinetic_energy_with_a_massless_contact() -> None:
    """Inverse dynamics takes the cam's contact parameter as massless (forward dynamics refuses it)."""
    scenario = scenarios.build("cam_roller", overrides={"steps": 40})
    analysis = analyse(scenario)
    assert analysis.layout.contacts
    extras = inverse_dynamics(scenario, analysis)
    (driver,) = scenario.drivers
    assert isinstance(driver, AbsoluteDriver) and driver.coordinate == "theta"
    column = analysis.layout.body_column(driver.body)
    assert column is not None
    bodies = 3 * len(scenario.bodies)
    power = extras[f"{driver.name}.force"] * analysis.qd[:, column + 2]
    expected = kinetic_rate(scenario, analysis.qd[:, :bodies], analysis.qdd[:, :bodies])
    scale = np.max(np.abs(expected))
    assert scale > 0
    np.testing.assert_allclose(power, expected, rtol=0, atol=1e-9 * scale)
