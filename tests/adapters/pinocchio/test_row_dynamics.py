"""Pinocchio's dynamic modes on gears and racks: forwardDynamics with the adapter's rows, RK4.

At constant speed every gear family moves linearly in time and RK4 integrates it exactly, so the
order is measured with a harmonic drive (theta = 0.5 sin(10 t)) against the native solver, an
independent engine: halving the step must divide the error by about 2^4."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

import scenarios
from adapters.base import Setting
from adapters.pinocchio import PinocchioAdapter
from adapters.reference import ReferenceAdapter
from scenarios.closed_form import exact
from scenarios.motions import Harmonic

GEARS = ("spur_gears", "spur_gears/internal", "planetary_gears", "rack_pinion")


@pytest.mark.parametrize("name", GEARS)
def test_constant_speed_gears_run_at_round_off(name: str) -> None:
    scenario = scenarios.build(name, overrides={"steps": 20})
    result = PinocchioAdapter().run(scenario, Setting.of("dynamic", dt=scenario.t_end / 100))
    assert result.status == "ok", result.message
    assert result.trajectory is not None
    truth = exact(scenario, result.trajectory.times).select(scenario.output_bodies)
    got = result.trajectory.select(scenario.output_bodies)
    assert np.abs(got.position - truth.position).max() < 1e-12


@pytest.mark.parametrize("name", GEARS)
def test_dynamic_mode_is_fourth_order_on_the_gears(name: str) -> None:
    scenario = scenarios.build(name, overrides={"steps": 10})
    (driver,) = scenario.drivers
    harmonic = Harmonic(mean=driver.motion.f(0.0), amplitude=0.5, omega=10.0, phase=-math.pi / 2)
    scenario = replace(scenario, drivers=(replace(driver, motion=harmonic),))
    truth = ReferenceAdapter().run(scenario, Setting.of("newton", tolerance=1e-14))
    assert truth.status == "ok" and truth.trajectory is not None
    errors = []
    for steps in (40, 80):
        result = PinocchioAdapter().run(scenario, Setting.of("dynamic", dt=scenario.t_end / steps))
        assert result.status == "ok", result.message
        assert result.trajectory is not None
        errors.append(np.abs(result.trajectory.position - truth.trajectory.position).max())
    order = math.log2(errors[0] / errors[1])
    assert 3.5 < order < 4.5, (errors, order)
