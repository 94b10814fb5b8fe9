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
from scenarios.drivers import AbsoluteDriver


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
