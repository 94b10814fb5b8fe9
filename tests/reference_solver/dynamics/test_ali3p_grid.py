"""ALI3-P over a time grid (dynamics.ali3p_grid) on motions whose answers are known in closed form.

A free body under gravity and a constant applied force moves with constant acceleration, which the
trapezoidal rule integrates exactly (its predictor q + h q' + h^2/2 q'' is already the answer) and
the quintic Hermite interpolant reproduces exactly between steps; the work of the force, F . (r - r0),
is exact at step ends (the power is linear in t) and interpolated linearly between them. Where no
closed form exists (a pendulum), the outputs at step ends are the plain step's own states, stepped
by hand at the step the grid must choose (span / ceil(span / step))."""

from __future__ import annotations

import numpy as np
import pytest

import scenarios
from reference_solver.compiled_system import constraint_system
from reference_solver.dynamics.ali3p import Ali3p, StepState
from reference_solver.dynamics.ali3p_grid import _interpolate, integrate
from reference_solver.dynamics.forward import initial_state
from reference_solver.dynamics.loads import Loads
from reference_solver.dynamics.mass import mass_diagonal
from scenarios import Body, Point, Scenario
from scenarios.forces import AppliedForce, AppliedTorque
from scenarios.motions import Constant, ConstantSpeed

G = (0.0, -9.81)
FORCE = (3.0, 1.5)
TORQUE = 0.2
MASS, INERTIA = 2.0, 0.1
START = np.array([0.3, -0.1, 0.2])
RATE = np.array([0.5, 2.0, 0.7])


def _free_body() -> Scenario:
    """A free body pushed by a constant force at its centre and a constant torque, the torque given
    as a law of time (ConstantSpeed with rate 0), which the loads read at each state's time."""
    body = Body("b", tuple(START), mass=MASS, inertia=INERTIA, rate=tuple(RATE))
    push = AppliedForce("push", Point("b"), Constant(FORCE[0]), Constant(FORCE[1]))
    turn = AppliedTorque("turn", "b", ConstantSpeed(TORQUE, 0.0))
    return Scenario(
        "free", "default", (body,), (), (), 1.0, 10, 1.0, gravity=G, forces=(push, turn), analysis="dynamic"
    )


def _setup(scenario: Scenario, t0: float = 0.0) -> tuple:
    system = constraint_system(scenario, compiled=False)
    mass = mass_diagonal(scenario, system.layout)
    loads = Loads(scenario, system.layout, mass)
    return system, mass, loads, initial_state(system, mass, loads, t0)


@pytest.mark.parametrize("t0", [0.0, 0.5])
def test_a_free_body_under_a_constant_force_on_a_grid_off_the_steps(t0: float) -> None:
    """Step 0.1 over 1 s from t0: 10 steps of one Newton iteration each (the predictor is exact);
    outputs inside steps (t0 + 0.013, 0.25, 0.77), on a step's end (t0 + 0.3, 1.0), two in one step
    (0.25 and 0.3)."""
    system, mass, loads, start = _setup(_free_body(), t0)
    grid = t0 + np.array([0.0, 0.013, 0.25, 0.3, 0.77, 1.0])
    states, works, evaluations = integrate(system, mass, loads, start, grid, 0.1)
    acceleration = np.array([FORCE[0] / MASS + G[0], FORCE[1] / MASS + G[1], TORQUE / INERTIA])
    applied = np.array([*FORCE, TORQUE])
    assert len(states) == grid.size and works.shape == (grid.size, 3)
    assert evaluations == 10
    for t, s in zip(grid, states, strict=True):
        assert s.t == pytest.approx(t, abs=1e-15)  # a step's end is its own time, sums of h
        dt = t - t0
        np.testing.assert_allclose(s.q, START + RATE * dt + acceleration * dt * dt / 2, rtol=0, atol=1e-13)
        np.testing.assert_allclose(s.qd, RATE + acceleration * dt, rtol=0, atol=1e-11)
        np.testing.assert_allclose(s.qdd, acceleration, rtol=0, atol=1e-9)
        assert s.lam.shape == (0,)
        assert s.loads.applied_power == pytest.approx(applied @ (RATE + acceleration * dt))
        np.testing.assert_allclose(s.loads.generalized, applied + MASS * np.array([*G, 0.0]), atol=1e-15)

    def work(dt: float) -> float:
        return float(applied @ (RATE * dt + acceleration * dt * dt / 2))

    # linear between the step ends around each output time
    expected = [0.0]
    for dt in grid[1:] - t0:
        a = np.floor(dt / 0.1 - 1e-9) * 0.1
        expected.append(work(a) + (dt - a) / 0.1 * (work(a + 0.1) - work(a)))
    np.testing.assert_allclose(works[:, 0], expected, rtol=1e-12, atol=1e-14)
    assert work(0.3) == pytest.approx(expected[3], rel=1e-12)  # on a step's end, the exact work
    np.testing.assert_array_equal(works[:, 1:], 0.0)
    assert states[-1].t == grid[-1]  # the last step ends on the grid's last time exactly


@pytest.mark.parametrize("t0", [0.0, 0.5])
@pytest.mark.parametrize(("step", "count"), [(0.3, 4), (0.25, 4), (0.26, 4), (2.0, 1)])
def test_the_step_is_the_span_over_the_fewest_steps_of_at_most_the_given_size(
    step: float, count: int, t0: float
) -> None:
    """One Newton iteration per step on the free body, so the evaluations count the steps over the
    span of 1 s from t0."""
    system, mass, loads, start = _setup(_free_body(), t0)
    _, _, evaluations = integrate(system, mass, loads, start, t0 + np.array([0.0, 0.4, 1.0]), step)
    assert evaluations == count


def test_outputs_on_step_ends_are_the_plain_steps_states() -> None:
    """A compound pendulum (constrained, not polynomial) on a grid of 0, 0.005, 0.01 at a step of at
    most 0.003: four steps of 0.0025, the outputs after the second and the fourth, with the
    multipliers the stepper gives at each state."""
    scenario = scenarios.build("compound_pendulum", overrides={"t_end": 0.01, "steps": 2})
    system, mass, loads, start = _setup(scenario)
    states, works, _ = integrate(system, mass, loads, start, np.array([0.0, 0.005, 0.01]), 0.003)
    stepper = Ali3p(system, mass, loads, 0.0025)
    s = StepState(start.t, start.q, start.qd, start.qdd, start.lam.copy(), start.jac)
    for k in range(1, 5):
        s = stepper.step(s)
        if k % 2 == 0:
            out = states[k // 2]
            assert out.t == pytest.approx(s.t, abs=1e-15)
            for x, y in ((out.q, s.q), (out.qd, s.qd), (out.qdd, s.qdd)):
                np.testing.assert_allclose(x, y, rtol=0, atol=1e-13)
            lam = stepper.multipliers(s, loads(s.q, s.qd, s.t).generalized)
            np.testing.assert_allclose(out.lam, lam, rtol=1e-9, atol=1e-9 * np.max(np.abs(lam)))
    np.testing.assert_array_equal(works, 0.0)  # no force elements, no drivers


def test_the_interpolant_reproduces_a_quintic() -> None:
    """q(t) = sum c_j (t - 0.2)^j, a quintic per coordinate, from q, q', q'' at t = 0.2 and 0.7:
    the state at 0.3 of the step is the quintic's, whatever the step, with C_q there (a compound
    pendulum's constraints, which the interpolant does not have to meet)."""
    system, *_ = _setup(scenarios.build("compound_pendulum"))
    n = system.layout.size
    rng = np.random.default_rng(11)
    c = rng.normal(size=(6, n))
    j = np.arange(6)[:, None]

    def at(t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        x = t - 0.2
        q = np.sum(c * x**j, axis=0)
        qd = np.sum(c[1:] * j[1:] * x ** (j[1:] - 1), axis=0)
        qdd = np.sum(c[2:] * j[2:] * (j[2:] - 1) * x ** (j[2:] - 2), axis=0)
        return q, qd, qdd

    lam = np.array([1.0, 2.0])
    a = StepState(0.2, *at(0.2), np.zeros(2), np.zeros((0, n)))
    b = StepState(0.7, *at(0.7), lam, np.zeros((0, n)))
    s = _interpolate(system, a, b, 0.3, 0.35)
    assert s.t == 0.35
    for x, y in zip((s.q, s.qd, s.qdd), at(0.35), strict=True):
        np.testing.assert_allclose(x, y, rtol=0, atol=1e-12)
    np.testing.assert_array_equal(s.multipliers, lam)
    np.testing.assert_allclose(s.jac, system.jacobian(at(0.35)[0], 0.35), rtol=0, atol=1e-12)
