"""ALI3-P's compiled step (dynamics.compiled_ali3p) over several steps at once (`run`): the state,
the driver power and its work integral against closed forms of a rod turned at constant speed and
against the plain step (dynamics.ali3p) with the trapezoidal rule on its own powers; which stepper
ali3p_stepper chooses; and the refusals (force elements, a W that is not positive definite)."""

from __future__ import annotations

import numpy as np
import pytest

import scenarios
from reference_solver.compiled.constraint_rows import NotCompiled
from reference_solver.compiled_system import CompiledSystem, constraint_system
from reference_solver.dynamics.ali3p import Ali3p, StepState
from reference_solver.dynamics.compiled_ali3p import CompiledAli3p
from reference_solver.dynamics.loads import Loads
from reference_solver.dynamics.mass import mass_diagonal
from reference_solver.dynamics.partition import State, driver_power
from reference_solver.errors import ConvergenceError
from scenarios.drivers import AbsoluteDriver
from scenarios.forces import RotationalSpringDamper
from scenarios.motions import ConstantSpeed
from tests.support.ali3p_rod import (
    MASS,
    SPEED,
    THETA0,
    G,
    compiled_stepper_at_rest,
    rod_stepper,
    swinging_rod,
)


def _power(stepper: Ali3p, loads: Loads, s: StepState) -> float:
    state = State(s.t, s.q, s.qd, s.qdd, s.multipliers, s.jac, loads(s.q, s.qd, s.t))
    return driver_power(stepper.system, state)


def test_run_gives_the_rod_s_motion_and_the_driver_s_power_and_work() -> None:
    """Turned at constant speed, the rod's kinetic energy is constant, so the driver's power is the
    rate of its potential energy, M g 0.5 cos(theta) SPEED, and its work M g 0.5 (sin theta -
    sin THETA0). ALI3-P's multipliers, and with them the power, are off by O(h) (measured after 200
    steps of 1e-3: power 2.5e-3 of 12.6 W, work 5.7e-4 of 1.87 J); the plain step, with the
    trapezoidal rule on its own powers, gives the same to round-off (measured: identical)."""
    h, count = 1e-3, 200
    stepper, loads, s = rod_stepper(swinging_rod(), True, h)
    assert isinstance(stepper, CompiledAli3p)
    power0 = np.array([0.0, 0.0, _power(stepper, loads, s)])
    assert power0[2] == pytest.approx(MASS * G * 0.5 * np.cos(THETA0) * SPEED, rel=1e-9)
    end, power, work = stepper.run(s, count, power0, np.array([0.0, 0.0, 0.25]))
    t = count * h
    theta = THETA0 + SPEED * t
    assert end.t == pytest.approx(t, abs=1e-14)
    assert end.q[2] == pytest.approx(theta, abs=1e-12)
    np.testing.assert_allclose(end.q[:2], 0.5 * np.array([np.cos(theta), np.sin(theta)]), atol=1e-12)
    assert end.qd[2] == pytest.approx(SPEED, abs=1e-8)
    assert power[:2].tolist() == [0.0, 0.0] and work[:2].tolist() == [0.0, 0.0]
    assert power[2] == pytest.approx(MASS * G * 0.5 * np.cos(theta) * SPEED, abs=6e-3)
    exact = MASS * G * 0.5 * (np.sin(theta) - np.sin(THETA0))
    assert work[2] - 0.25 == pytest.approx(exact, abs=1.5e-3)
    plain, plain_loads, s_plain = rod_stepper(swinging_rod(), False, h)
    plain_power, plain_work = power0[2], 0.25
    for _ in range(count):
        s_plain = plain.step(s_plain)
        now = _power(plain, plain_loads, s_plain)
        plain_work += h / 2 * (plain_power + now)
        plain_power = now
    assert power[2] == pytest.approx(plain_power, rel=1e-12)
    assert work[2] == pytest.approx(plain_work, rel=1e-12)
    np.testing.assert_allclose(end.multipliers, s_plain.multipliers, rtol=1e-10)
    np.testing.assert_allclose(end.jac, stepper.system.jacobian(end.q, end.t), rtol=0, atol=1e-15)
    assert end.iterations >= 1 and stepper.evaluations >= count


def test_run_is_the_plain_step_repeated_with_the_trapezoidal_work() -> None:
    """On a chain without force elements: `run` over 30 steps against the plain step taken 30 times,
    its driver power at each and their trapezoidal integral (none here: n_four_bar is free)."""
    h, count = 1e-3, 30
    scenario = scenarios.build("n_four_bar", overrides={"loops": 3, "t_end": 0.1, "steps": 2})
    compiled, _, s = rod_stepper(scenario, True, h)
    plain, _, s_plain = rod_stepper(scenario, False, h)
    assert isinstance(compiled, CompiledAli3p) and not isinstance(plain, CompiledAli3p)
    end, _, _ = compiled.run(s, count, np.zeros(3), np.zeros(3))
    for _ in range(count):
        s_plain = plain.step(s_plain)
    scale = plain.system.layout.length_scale
    assert end.t == pytest.approx(s_plain.t, abs=1e-14)
    assert np.max(np.abs(end.q - s_plain.q)) < 1e-11 * scale
    assert np.max(np.abs(end.qd - s_plain.qd)) * h / 2 < 1e-11 * scale
    np.testing.assert_allclose(compiled.alpha, plain.alpha, rtol=1e-12)
    assert compiled.slow_steps == 0


def test_the_stepper_is_compiled_only_for_compiled_systems_without_force_elements() -> None:
    scenario = swinging_rod()
    h = 1e-3
    assert type(rod_stepper(scenario, False, h)[0]) is Ali3p
    sprung = scenarios.Scenario(
        "rod",
        "default",
        scenario.bodies,
        scenario.joints,
        scenario.drivers,
        1.0,
        10,
        1.0,
        gravity=(0.0, -G),
        analysis="dynamic",
        forces=(RotationalSpringDamper("t", "ground", "rod", 1.0, 0.1),),
    )
    assert type(rod_stepper(sprung, True, h)[0]) is Ali3p
    system = constraint_system(sprung)
    assert isinstance(system, CompiledSystem)
    mass = mass_diagonal(sprung, system.layout)
    with pytest.raises(
        NotCompiled, match=r"^ALI3-P's compiled step takes no force elements \(W would not be symmetric\)$"
    ):
        CompiledAli3p(system, mass, Loads(sprung, system.layout, mass), h, object())  # type: ignore[arg-type]


def test_a_w_that_is_not_positive_definite_is_refused() -> None:
    """Masses far below zero, once the penalties are fixed by a first step, make W negative
    definite: the kernel's refusal is a LinAlgError, not a state."""
    stepper, _, s = rod_stepper(swinging_rod(), True, 1e-3)
    assert isinstance(stepper, CompiledAli3p)
    s = stepper.step(s)
    stepper.vec[stepper.kernels.MASS, : stepper.n] = -1e9
    with pytest.raises(np.linalg.LinAlgError, match=r"^ALI3-P's iteration matrix is not positive definite$"):
        stepper.step(s)


def test_the_evaluations_add_up_over_runs_and_solve_takes_integers() -> None:
    """Two runs count every constraint evaluation of both (the kernel's own counter, which only
    grows); solve reads an integer right-hand side as its values (W x = b to round-off)."""
    stepper, _, s = rod_stepper(swinging_rod(), True, 1e-3)
    assert isinstance(stepper, CompiledAli3p)
    s, _, _ = stepper.run(s, 3, np.zeros(3), np.zeros(3))
    first = stepper.evaluations
    stepper.run(s, 2, np.zeros(3), np.zeros(3))
    assert first >= 3 and stepper.evaluations >= first + 2
    assert stepper.evaluations == int(stepper.sizes[stepper.kernels.S_EVALUATIONS])
    b = np.arange(1, stepper.n + 1)
    np.testing.assert_allclose(stepper.solve(b), stepper.solve(b.astype(float)), rtol=1e-15)
    assert np.abs(stepper.solve(b)).max() > 0


def test_the_half_bandwidth_covers_every_row_of_the_jacobian() -> None:
    """W's half-bandwidth is at least the widest row of C_q (columns of its nonzeros, from the plain
    Jacobian at a state), so the banded factor holds every coupling."""
    scenario = scenarios.build("n_four_bar", overrides={"loops": 3, "t_end": 0.1, "steps": 2})
    stepper, _, s = rod_stepper(scenario, True, 1e-3)
    assert isinstance(stepper, CompiledAli3p)
    jac = constraint_system(scenario, compiled=False).jacobian(s.q, s.t)
    widest = max(int(np.ptp(np.flatnonzero(row))) for row in jac if np.any(row))
    width = int(stepper.sizes[stepper.kernels.S_W])
    assert widest <= width < stepper.n
    assert stepper.band.shape == (stepper.n, width + 1)


def test_a_step_newton_cannot_finish_is_refused_with_where() -> None:
    """The rod held at a fixed angle by one driver while another moves its centre along x at 5 m/s:
    after t = 0 no position meets both (the centre stays 0.5 m from the pin), so Newton cannot
    finish the first step; the refusal names the scenario, the step's end time, and gives it and
    the last positions."""
    h = 1e-3
    rod = swinging_rod()
    slide = AbsoluteDriver("slide", "rod", "x", ConstantSpeed(0.5 * np.cos(THETA0), 5.0))
    turn = AbsoluteDriver("turn", "rod", "theta", ConstantSpeed(THETA0, 0.0))
    scenario = scenarios.Scenario(
        "rod",
        "default",
        rod.bodies,
        rod.joints,
        (turn, slide),
        1.0,
        10,
        1.0,
        gravity=(0.0, -G),
        analysis="dynamic",
    )
    stepper, s = compiled_stepper_at_rest(scenario, h)
    with pytest.raises(ConvergenceError) as caught:
        stepper.step(s)
    assert str(caught.value) == "rod: ALI3-P's Newton iteration did not converge at t=0.001"
    assert caught.value.time == pytest.approx(h, abs=1e-18)
    assert caught.value.q is not None and caught.value.q.shape == (3,) and np.all(np.isfinite(caught.value.q))
