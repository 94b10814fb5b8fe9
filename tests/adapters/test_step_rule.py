"""The one settings rule (adapters.step_rule): the shortest period from closed forms, and the output
grid never changing how an engine integrates."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import adapters
import scenarios
from adapters.lattice import hermite, lattice_point, lattice_steps
from adapters.step_rule import FALLBACK_PERIOD, rule_step, shortest_period
from tests.support.engines import COMPARED

STEPS_ON_OUTPUTS = ("exudyn", "drake")
"""The engines whose step is shortened to put an even grid's outputs on it (outputs_on_steps)."""


def test_a_driven_mechanism_s_period_is_one_turn_of_its_crank() -> None:
    scenario = scenarios.build("slider_crank", overrides={"omega": 20.0})
    assert shortest_period(scenario) == pytest.approx(2 * math.pi / 20.0, rel=1e-15)
    assert rule_step(scenario, 1000) == pytest.approx(2 * math.pi / 20.0 / 1000, rel=1e-15)


def test_a_polynomial_drive_s_period_is_its_fastest_term_s_turn() -> None:
    """f = 0.3 + 20 t + 400 t^2: the linear term turns in 2 pi / 20 s, the quadratic one alone
    advances 2 pi in sqrt(2 pi / 400) s, the shorter; a pure constant speed is its turn."""
    base = scenarios.build("slider_crank")
    drive = base.drivers[0]

    def period(*coefficients: float) -> float:
        motion = scenarios.Polynomial(coefficients)
        return shortest_period(
            dataclasses.replace(base, drivers=(dataclasses.replace(drive, motion=motion),))
        )

    assert period(0.3, 20.0, 400.0) == pytest.approx(math.sqrt(2 * math.pi / 400.0), rel=1e-15)
    assert period(0.3, -20.0) == pytest.approx(2 * math.pi / 20.0, rel=1e-15)
    assert period(0.3, 0.0, 0.0, -8.0) == pytest.approx((2 * math.pi / 8.0) ** (1 / 3), rel=1e-15)
    assert period(0.3) == FALLBACK_PERIOD


def test_a_free_spring_s_period_is_its_mode() -> None:
    scenario = scenarios.load("stiff_spring/k1e4_dt1e-3")
    (body,) = scenario.bodies
    (spring,) = scenario.forces
    expected = 2 * math.pi * math.sqrt(body.mass / spring.stiffness)  # type: ignore[union-attr]
    assert shortest_period(scenario) == pytest.approx(expected, rel=1e-12)


def test_a_hanging_chain_s_period_is_its_stiffest_gravity_mode() -> None:
    scenario = scenarios.build("compound_pendulum", overrides={"links": 9})
    length = min(b.length for b in scenario.bodies)
    assert shortest_period(scenario) == pytest.approx(math.pi / math.sqrt(9 * 9.81 / length), rel=1e-3)


def test_the_grid_is_not_an_input_of_the_rule() -> None:
    scenario = scenarios.load("four_bar_gravity")
    other = dataclasses.replace(scenario, t_end=0.2, steps=4)
    assert shortest_period(other) == shortest_period(scenario)


def test_nothing_that_sets_a_time_falls_back_to_one_second() -> None:
    scenario = scenarios.load("four_bar_gravity")
    weightless = dataclasses.replace(scenario, gravity=(0.0, 0.0))
    assert shortest_period(weightless) == FALLBACK_PERIOD


def test_lattice_points_and_remainders() -> None:
    assert lattice_point(0.0, 0.3, 0.1) == (3, 0.0)  # 0.3 / 0.1 = 2.9999999999999996: on the lattice
    k, rest = lattice_point(0.0, 0.25, 0.1)
    assert k == 2 and rest == pytest.approx(0.05, rel=1e-12)
    assert lattice_steps(0.0, 0.25, 0.1) == 3 and lattice_steps(0.0, 0.3, 0.1) == 3


def test_interpolation_between_steps_is_exact_on_a_cubic() -> None:
    """Cubic Hermite in (q, v) and (v, a), linear in a: exact when q is a cubic."""
    p = np.polynomial.Polynomial([0.3, -1.0, 2.0, 0.5])
    ends = [tuple(np.array([f(t)]) for f in (p, p.deriv(), p.deriv(2))) for t in (1.0, 1.5)]
    q, v, a = hermite(0.3, 0.5, ends[0], ends[1])
    assert q[0] == pytest.approx(p(1.15), abs=1e-14)
    assert v[0] == pytest.approx(p.deriv()(1.15), abs=1e-14)
    assert a[0] == pytest.approx(p.deriv(2)(1.15), abs=1e-14)


def test_interpolation_does_not_amplify_a_velocity_error() -> None:
    """An integrator's velocity error must not reach the accelerations divided by the step."""
    ends = [(np.zeros(1), np.array([1e-6]), np.zeros(1)), (np.zeros(1), np.zeros(1), np.zeros(1))]
    _, _, a = hermite(0.5, 1e-5, ends[0], ends[1])
    assert abs(a[0]) < 1e-12


@pytest.mark.parametrize("engine", COMPARED)
def test_steps_do_not_depend_on_the_output_grid(engine: str) -> None:
    """The issue's case: four_bar_gravity with t_end 0.2 and 4 steps against t_end 0.4 and 16 steps
    (before: 1.5e-2 apart in Exudyn, 1.6e-5 in Pinocchio). The same march: the same states at the
    common times, to round-off. Exudyn and Drake read their outputs on their own steps (the rule's
    step shortened to divide the output spacing, adapters.lattice.outputs_on_steps): their march is
    the same for the same spacing, so their longer grid keeps the spacing (8 steps)."""
    adapter = adapters.load(engine)
    if not adapter.dynamics:
        pytest.skip(f"{engine} does not run forward dynamics")
    scenario = scenarios.load("four_bar_gravity")
    short = dataclasses.replace(scenario, t_end=0.2, steps=4)
    every = 1 if engine in STEPS_ON_OUTPUTS else 2
    long = dataclasses.replace(scenario, t_end=0.4, steps=8 * every)
    assert adapter.default_setting(short) == adapter.default_setting(long)
    runs = [adapter.run(s) for s in (short, long)]
    assert all(r.status == "ok" and r.trajectory is not None for r in runs), [r.message for r in runs]
    first, second = (r.trajectory for r in runs)
    assert first is not None and second is not None
    for level in ("position", "velocity", "acceleration"):
        mine, theirs = first.level(level), second.level(level)
        assert mine is not None and theirs is not None
        np.testing.assert_allclose(mine, theirs[::every][:5], rtol=1e-12, atol=1e-12, err_msg=level)


@pytest.mark.parametrize("engine", ("mujoco", "pinocchio"))
def test_a_driven_mechanism_s_outputs_do_not_depend_on_the_grid(engine: str) -> None:
    """A grid whose interval is not a whole number of steps (outputs by side steps) against one
    holding every other of its times."""
    adapter = adapters.load(engine)
    scenario = scenarios.build("slider_crank", overrides={"steps": 40})
    setting = adapter.ladder(scenario)[-1] if engine == "pinocchio" else adapter.default_setting(scenario)
    coarse = adapter.run(scenario, setting, np.asarray(scenario.times())[::2])
    fine = adapter.run(scenario, setting, np.asarray(scenario.times()))
    assert coarse.trajectory is not None and fine.trajectory is not None, (coarse.message, fine.message)
    np.testing.assert_allclose(coarse.trajectory.position, fine.trajectory.position[::2], rtol=0, atol=1e-13)


@pytest.mark.parametrize("engine", COMPARED)
def test_a_grid_that_goes_back_in_time_is_a_failed_run(engine: str) -> None:
    adapter = adapters.load(engine)
    scenario = scenarios.load("four_bar_gravity" if adapter.dynamics else "four_bar")
    result = adapter.run(scenario, times=np.array([0.0, 0.02, 0.01]))
    assert result.status == "failed" and "must rise" in result.message
