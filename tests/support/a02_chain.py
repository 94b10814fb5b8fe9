"""The A02 chain (n_four_bar) for ALI3-P's tests: the chain, its errors against the
one-degree-of-freedom solution, a scenario moved along x, and steps compared in metres and
kilometres."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace

import numpy as np
from scipy.integrate import solve_ivp

import scenarios
from reference_solver.dynamics import DynamicAnalysis
from reference_solver.dynamics.ali3p import Ali3p, StepState
from scenarios.bodies import GROUND, Point

FACTOR = 3.0


def a02_chain(loops: int, t_end: float) -> tuple[scenarios.Scenario, np.ndarray, object]:
    """n_four_bar with `loops` loops over t_end, its grid with the passage times added, and the
    one-degree-of-freedom solution (dense, theta and theta')."""
    scenario = scenarios.build("n_four_bar", overrides={"loops": loops, "t_end": t_end, "steps": 20})
    inertia, weight = (loops + 1) / 3 + loops, 9.81 * ((loops + 1) / 2 + loops)
    reduced = solve_ivp(
        lambda t, y: [y[1], -weight / inertia * np.cos(y[0])],
        (0.0, t_end),
        [np.pi / 2, -1.0],
        method="DOP853",
        rtol=1e-13,
        atol=1e-13,
        events=lambda t, y: np.sin(y[0]),
        dense_output=True,
    )
    return scenario, np.union1d(scenario.times(), reduced.t_events[0]), reduced


def a02_errors(analysis: DynamicAnalysis, reduced: object) -> tuple[float, float, float]:
    """Energy drift over the largest kinetic energy, the largest angle of any rocker to the crank,
    and the crank's distance to the one-degree-of-freedom solution."""
    extras = analysis.extras
    energy = extras["energy.kinetic"] + extras["energy.potential"]
    drift = float(np.max(np.abs(energy - energy[0])) / np.max(extras["energy.kinetic"]))
    theta = analysis.q[:, 2::3]
    rockers = [k for k, body in enumerate(analysis.layout.bodies) if body.startswith("rocker")]
    parallel = float(np.max(np.abs(theta[:, rockers] - theta[:, :1])))
    crank = float(np.max(np.abs(theta[:, 0] - reduced.sol(analysis.times)[0])))  # type: ignore[attr-defined]
    return drift, parallel, crank


def steps_alike_in_metres_and_kilometres(
    stepper_of: Callable[[scenarios.Scenario, float], tuple[Ali3p, StepState]],
) -> None:
    """Asserts that 5 steps of h = 1e-3 by `stepper_of`'s stepper (of a scenario and h, with its
    start) take as many Newton iterations on the compound pendulum with links of 1 m under g = 9.81
    as with links of 1 km under g = 9.81e3, to the same angles and a thousand times the lengths."""
    runs = []
    for length in (1.0, 1e3):
        overrides = {"link_length": length, "gravity": 9.81 * length, "t_end": 0.01, "steps": 2}
        stepper, s = stepper_of(scenarios.build("compound_pendulum", overrides=overrides), 1e-3)
        states = []
        for _ in range(5):
            s = stepper.step(s)
            states.append(s)
        runs.append(states)
    for metre, kilometre in zip(*runs, strict=True):
        assert metre.iterations == kilometre.iterations
        np.testing.assert_allclose(kilometre.q[2::3], metre.q[2::3], rtol=0, atol=1e-12)
        np.testing.assert_allclose(kilometre.q[0::3] / 1e3, metre.q[0::3], rtol=0, atol=1e-12)
        np.testing.assert_allclose(kilometre.q[1::3] / 1e3, metre.q[1::3], rtol=0, atol=1e-12)


def moved_along_x(scenario: scenarios.Scenario, dx: float) -> scenarios.Scenario:
    """The scenario moved dx along x: every body and every ground point."""
    bodies = tuple(replace(b, guess=(b.guess[0] + dx, *b.guess[1:])) for b in scenario.bodies)

    def point(p: Point) -> Point:
        return Point(GROUND, (p.local[0] + dx, p.local[1])) if p.body == GROUND else p

    joints = tuple(replace(j, p_i=point(j.p_i), p_j=point(j.p_j)) for j in scenario.joints)
    return replace(scenario, bodies=bodies, joints=joints)
