"""Forward dynamics (dynamics.forward): a free body falls as y = -g t^2 / 2 and flies its parabola;
the refusals by name; the initial rates nearest the given ones; a driven chain's energy balance."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import scenarios
from reference_solver.dynamics.forward import simulate
from reference_solver.dynamics.partition import Partitioned
from reference_solver.errors import SolverError
from scenarios import AbsoluteDriver, Body, Constant, ConstantSpeed, Scenario
from scenarios.forces import AppliedTorque
from scenarios.outputs import AngleOutput
from tests.support.forward_scenes import nearest_turn, rod, thrown_rod

G = 9.81


@pytest.mark.parametrize(("method", "compiled"), [("DOP853", False), ("DOP853", True), ("ali3p", False)])
def test_a_free_body_falls_as_the_closed_form(method: str, compiled: bool) -> None:
    """Each method used to end in a crash (the largest residual of no rows) after integrating."""
    body = Body("b", (0.3, 0.0, 0.2), mass=2.0, inertia=0.1)
    scenario = Scenario(
        "free", "default", (body,), (), (), 1.0, 10, 1.0, gravity=(0.0, -G), analysis="dynamic"
    )
    result = simulate(scenario, method=method, compiled=compiled, step=1e-2 if method == "ali3p" else None)
    t = np.linspace(0.0, 1.0, 11)
    np.testing.assert_allclose(result.q[:, 1], -0.5 * G * t**2, rtol=0, atol=1e-12)
    np.testing.assert_allclose(result.q[:, [0, 2]], np.tile([0.3, 0.2], (11, 1)), rtol=0, atol=1e-15)
    # ALI3-P derives q'' from rate differences over its step: round-off 3.2e-12 relative, measured
    np.testing.assert_allclose(result.qdd[:, 1], -G, rtol=1e-11)
    assert np.all(result.motion.residual == 0.0) and result.lam.shape == (11, 0)


@pytest.mark.parametrize(
    ("options", "message"),
    [
        ({"method": "RK45"}, "unknown integrator 'RK45' (known: DOP853, Radau, ali3p)"),
        ({"step": 0.0}, "ALI3-P's step must be a positive number of seconds, not 0.0"),
        ({"step": -1e-3}, "ALI3-P's step must be a positive number of seconds, not -0.001"),
        ({"step": math.nan}, "ALI3-P's step must be a positive number of seconds, not nan"),
        ({"step": math.inf}, "ALI3-P's step must be a positive number of seconds, not inf"),
    ],
)
def test_bad_options_are_refused_by_name(options: dict[str, object], message: str) -> None:
    with pytest.raises(SolverError) as caught:
        simulate(rod(), **options)  # type: ignore[arg-type]
    assert str(caught.value) == message


def test_a_driven_rod_has_no_degree_of_freedom_left_to_forward_dynamics() -> None:
    held = rod(drivers=(AbsoluteDriver("hold", "link_1", "theta", Constant(-1.0)),))
    with pytest.raises(SolverError) as caught:
        simulate(held)
    assert str(caught.value) == "compound_pendulum: no degree of freedom is left to forward dynamics"


def test_the_initial_rates_are_the_given_ones_nearest_in_kinetic_energy() -> None:
    """The rod's rates are omega (a, 1) with a = l/2 (-sin, cos): the nearest to a given (v, w) in
    the metric diag(m, m, J) has omega = (m a . v + J w) / (m |a|^2 + J)."""
    body, start, theta = thrown_rod()
    a, omega = nearest_turn(body, theta)
    np.testing.assert_allclose(start.qd, [*(omega * a), omega], rtol=1e-14, atol=1e-15)
    # about the pin: theta'' = -(3 g / (2 l)) cos theta
    assert start.qdd[2] == pytest.approx(-1.5 * G / 0.5 * math.cos(theta), rel=1e-13)


def test_a_thrown_free_body_follows_its_parabola_and_keeps_its_energy(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """Also counts the right-hand sides the integrator asks for (`evaluations`)."""
    calls: list[float] = []
    rates = Partitioned.rates

    def counting(self: Partitioned, t: float, y: np.ndarray) -> np.ndarray:
        calls.append(t)
        return rates(self, t, y)

    monkeypatch.setattr(Partitioned, "rates", counting)
    body = Body("b", (0.3, 0.0, 0.2), mass=2.0, inertia=0.1, rate=(1.5, 4.0, -2.0))
    scenario = Scenario(
        "free", "default", (body,), (), (), 0.5, 5, 1.0, gravity=(0.0, -G), analysis="dynamic"
    )
    result = simulate(scenario)
    t = np.linspace(0.0, 0.5, 6)
    wanted = np.stack([0.3 + 1.5 * t, 4.0 * t - 0.5 * G * t**2, 0.2 - 2.0 * t], axis=1)
    np.testing.assert_allclose(result.q, wanted, rtol=0, atol=1e-13)
    kinetic = 0.5 * 2.0 * (1.5**2 + (4.0 - G * t) ** 2) + 0.5 * 0.1 * 4.0
    np.testing.assert_allclose(result.extras["energy.kinetic"], kinetic, rtol=1e-13)
    np.testing.assert_allclose(result.extras["energy.potential"], 2.0 * G * wanted[:, 1], rtol=0, atol=1e-12)
    np.testing.assert_allclose(result.extras["energy.balance"], 0.0, atol=1e-12)
    assert result.partitions == 1 and result.evaluations == len(calls) > 0
    np.testing.assert_array_equal(result.times, scenario.times())


def driven_chain(t_end: float) -> Scenario:
    """compound_pendulum's two links, the first turned at 2 rad/s by a driver, the second free,
    with its joint angle as an output."""
    chain = scenarios.build(
        "compound_pendulum", overrides={"links": 2, "theta0": 0.3, "t_end": t_end, "steps": 4}
    )
    spin = AbsoluteDriver("spin", "link_1", "theta", ConstantSpeed(0.3 - math.pi / 2, 2.0))
    elbow = AngleOutput("elbow", "link_2", "link_1")
    swing = AngleOutput("swing", "link_2")
    return dataclasses.replace(chain, drivers=(spin,), angle_outputs=(elbow, swing))


@pytest.mark.parametrize("compiled", [False, True])
def test_a_driven_chain_s_energy_is_what_its_driver_puts_in(compiled: bool) -> None:
    """T + V - (T0 + V0) = W_driver: the balance closes to round-off of the integration (rtol 1e-12)
    while the driver's work is of order 1 J, and the driven link turns as prescribed."""
    result = simulate(driven_chain(0.4), compiled=compiled)
    extras = result.extras
    work = extras["energy.driver_work"]
    assert np.max(np.abs(work)) > 0.1
    energy = extras["energy.kinetic"] + extras["energy.potential"]
    np.testing.assert_allclose(energy - energy[0], work, rtol=0, atol=1e-9 * np.max(np.abs(work)))
    np.testing.assert_allclose(extras["energy.balance"], 0.0, atol=1e-9 * np.max(np.abs(work)))
    t = np.linspace(0.0, 0.4, 5)
    np.testing.assert_allclose(result.q[:, 2], 0.3 - math.pi / 2 + 2.0 * t, rtol=0, atol=1e-13)
    np.testing.assert_allclose(extras["elbow"], result.q[:, 5] - result.q[:, 2], rtol=0, atol=0)
    np.testing.assert_array_equal(extras["swing"], result.q[:, 5])  # from the ground's angle, 0
    assert extras["pin_1.fx"].shape == extras["pin_2.fy"].shape == (5,)
    assert np.all(np.isfinite(extras["pin_1.fx"])) and np.max(np.abs(extras["pin_2.fy"])) > 0
    trajectory = result.trajectory(["link_2"])
    assert trajectory.bodies == ("link_2",)
    np.testing.assert_array_equal(trajectory.position[:, 0], result.q[:, 3:6])  # type: ignore[index]
    np.testing.assert_array_equal(trajectory.extras["energy.driver_work"], work)
    assert result.layout is result.motion.layout


@dataclasses.dataclass(frozen=True)
class UndefinedAfter:
    """A torque law of 1 N m that is undefined (NaN) after `end`, as a table read past its end."""

    end: float

    def f(self, t: float) -> float:
        return math.nan if t > self.end else 1.0

    def df(self, t: float) -> float:
        return math.nan if t > self.end else 0.0


def test_an_integrator_failure_names_the_scenario_and_where_it_started() -> None:
    """NaN rates after 0.02 s: DOP853 shrinks its step below the spacing of floats and gives up."""
    body = Body("b", (0.0, 0.0, 0.0), mass=1.0, inertia=0.1)
    motor = AppliedTorque("motor", "b", UndefinedAfter(0.02))  # type: ignore[arg-type]
    scenario = Scenario("free", "default", (body,), (), (), 0.1, 2, 1.0, forces=(motor,), analysis="dynamic")
    with pytest.raises(SolverError) as caught:
        simulate(scenario)
    assert str(caught.value) == (
        "free: the integrator failed after t=0: Required step size is less than spacing between numbers."
    )
