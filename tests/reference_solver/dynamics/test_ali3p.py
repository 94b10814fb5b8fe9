"""ALI3-P, the second native forward-dynamics method: the same motion as the partitioned method where
that one works (second order in the step, so halving the step divides its distance by 4 and the
Richardson combination of the two agrees far closer), and IFToMM A02 through its singular passages,
judged against the chain's own one-degree-of-freedom equation (every rocker turns with the crank,
couplers translate: I theta'' = -c cos theta, I = (N + 1)/3 + N, c = g ((N + 1)/2 + N) for links
of 1 m and 1 kg), which also gives the passage times (theta a multiple of pi)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import scenarios
from reference_solver.dynamics import DynamicAnalysis, ali3p_grid, simulate
from reference_solver.dynamics.ali3p import Ali3p
from reference_solver.errors import SolverError

SHORT = {
    # scenario: (t_end, steps, step h), and the measured distance to the partitioned method at h/2
    # per level (positions over the characteristic length, rates in SI, multipliers over their
    # largest); the distances of the Richardson combination (4 x_{h/2} - x_h) / 3 are all far smaller
    "four_bar_gravity": (0.1, 2, 2.5e-4, (9.12e-07, 4.87e-07, 2.38e-05, 3.89e-08)),
    "compound_pendulum": (0.2, 2, 5e-4, (3.77e-07, 7.04e-07, 2.06e-05, 1.96e-07)),
    "slider_crank_spring": (0.05, 2, 2.5e-4, (1.13e-05, 3.38e-05, 1.97e-03, 1.37e-06)),
    "andrews_squeezer": (0.0005, 1, 5e-6, (1.49e-08, 8.50e-07, 9.42e-05, 1.49e-10)),
}
RICHARDSON = {
    "four_bar_gravity": (1.10e-09, 1.28e-09, 4.63e-08, 1.64e-09),
    "compound_pendulum": (1.29e-10, 8.00e-10, 1.05e-08, 1.54e-09),
    "slider_crank_spring": (8.21e-09, 1.22e-07, 4.87e-06, 2.40e-09),
    "andrews_squeezer": (6.17e-13, 7.84e-11, 1.18e-06, 3.48e-13),
}
FACTOR = 3.0
A02_REDUCED = (8.57e-08, 1.43e-12, 4.54e-08)
"""2 loops over 0.8 s (one passage) at h = 1e-4: energy drift over the largest kinetic energy, the
largest rocker-to-crank angle, the crank's distance to the reduced equation (rad)."""


def _distances(
    scenario: scenarios.Scenario, ref: DynamicAnalysis, levels: tuple[np.ndarray, ...]
) -> np.ndarray:
    q, qd, qdd, lam = levels
    return np.array(
        [
            np.max(np.abs(q - ref.q)) / scenario.characteristic_length,
            np.max(np.abs(qd - ref.qd)),
            np.max(np.abs(qdd - ref.qdd)),
            np.max(np.abs(lam - ref.lam)) / np.max(np.abs(ref.lam)),
        ]
    )


@pytest.mark.parametrize("name", sorted(SHORT))
def test_the_same_motion_as_the_partitioned_method_to_second_order(name: str) -> None:
    t_end, steps, h, measured = SHORT[name]
    scenario = scenarios.build(name, overrides={"t_end": t_end, "steps": steps})
    ref = simulate(scenario, rtol=1e-12, fast=True)
    coarse = simulate(scenario, method="ali3p", step=h, fast=True)
    fine = simulate(scenario, method="ali3p", step=h / 2, fast=True)
    levels = ("q", "qd", "qdd", "lam")
    far = _distances(scenario, ref, tuple(getattr(coarse, k) for k in levels))
    near = _distances(scenario, ref, tuple(getattr(fine, k) for k in levels))
    order = np.log2(far / near)
    assert np.all((order > 1.9) & (order < 2.1)), f"observed order {order}"
    assert np.all(near < FACTOR * np.array(measured)), near
    assert np.all(near > np.array(measured) / FACTOR), near
    extrapolated = tuple((4 * getattr(fine, k) - getattr(coarse, k)) / 3 for k in levels)
    assert np.all(_distances(scenario, ref, extrapolated) < FACTOR * np.array(RICHARDSON[name]))


def test_constraints_hold_to_round_off_and_the_energy_balance_closes_to_second_order() -> None:
    scenario = scenarios.build("slider_crank_spring", overrides={"t_end": 0.05, "steps": 2})
    balances = []
    for h in (2.5e-4, 1.25e-4):
        analysis = simulate(scenario, method="ali3p", step=h, fast=True)
        assert np.max(analysis.motion.residual) < 1e-14
        balances.append(np.max(np.abs(analysis.extras["energy.balance"])))
    assert 3.6 < balances[0] / balances[1] < 4.4, balances


def _chain(loops: int, t_end: float) -> tuple[scenarios.Scenario, np.ndarray, object]:
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


def _a02_errors(analysis: DynamicAnalysis, reduced: object) -> tuple[float, float, float]:
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


def test_a_reduced_a02_passes_its_singular_position_at_second_order() -> None:
    scenario, grid, reduced = _chain(2, 0.8)
    assert len(reduced.t_events[0]) == 1  # type: ignore[attr-defined]
    coarse = _a02_errors(simulate(scenario, grid, method="ali3p", step=2e-4, fast=True), reduced)
    fine = _a02_errors(simulate(scenario, grid, method="ali3p", step=1e-4, fast=True), reduced)
    order = np.log2(np.array(coarse[::2]) / np.array(fine[::2]))  # energy drift and crank angle
    assert np.all((order > 1.8) & (order < 2.3)), order
    measured = np.array(A02_REDUCED)
    assert np.all((np.array(fine) < FACTOR * measured) & (np.array(fine) > measured / FACTOR)), fine


@pytest.mark.parametrize(
    ("count", "plain", "compiled"), [(8000, 1.43e-12, 2.24e-12), (8005, 3.60e-9, 1.03e-10)]
)
def test_the_rockers_leave_the_crank_by_what_the_step_s_phase_at_the_passage_allows(
    count: int, plain: float, compiled: float, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The rocker-to-crank angle is not a smooth function of h: it depends on where the singular
    instant falls within a step. 8000 steps over 0.8 s put it at 0.55 of a step, 8005 steps at 0.02
    (a step ends next to the singular configuration, where C_q holds the chain's extra freedoms only
    to second order). The plain step stops there at its stalled augmented Lagrangian: measured
    1.4e-12 and 3.6e-9 (at 0.34, 0.23, 0.81 of a step: 1.4e-11, 2.0e-11, 2.4e-10; at h = 5e-5 with
    the instant at 0.11 and 0.004 of a step: 1.2e-9, 8.4e-10). The compiled step continues through
    the Schur complement (fast.ali3p_kernel): measured 2.2e-12 and 1.0e-10."""
    scenario, grid, reduced = _chain(2, 0.8)
    step = 0.8 / count * (1 + 1e-9)
    analysis = simulate(scenario, grid, method="ali3p", step=step, fast=True)
    assert compiled / FACTOR < _a02_errors(analysis, reduced)[1] < FACTOR * compiled
    monkeypatch.setattr(ali3p_grid, "ali3p_stepper", Ali3p)  # the plain step on the same rows
    analysis = simulate(scenario, grid, method="ali3p", step=step, fast=True)
    assert plain / FACTOR < _a02_errors(analysis, reduced)[1] < FACTOR * plain


def test_unknown_method_and_bad_step_are_refused() -> None:
    scenario = scenarios.build("compound_pendulum", overrides={"t_end": 0.01, "steps": 1})
    with pytest.raises(SolverError, match="ali3p"):
        simulate(scenario, method="ali3")
    with pytest.raises(SolverError, match="positive"):
        simulate(scenario, method="ali3p", step=0.0)


A02_SPEC = (6.03e-09, 6.72e-10, 2.07e-07)
"""n_four_bar/spec (40 loops, 20 s, 20 singular passages) at h = 2e-5 on 400 output steps and the
passage times, on the compiled step: energy drift over the largest kinetic energy, the largest
rocker-to-crank angle (at a passage: a step ends next to one), the crank's distance to the reduced
equation. Measured 108 s CPU on a loaded machine (load average 13 on 2 cores). The plain step at
h = 2e-4 (56 s CPU): 4.3e-7, 1.7e-8, 8.1e-6; at h = 1e-4 (112 s): 1.07e-7, 5.4e-9, 3.0e-6."""


@pytest.mark.slow
def test_a02_as_specified_passes_every_singular_position() -> None:
    scenario = scenarios.build("n_four_bar/spec", overrides={"steps": 400})
    _, _, reduced = _chain(40, scenario.t_end)
    passages = reduced.t_events[0]  # type: ignore[attr-defined]
    assert len(passages) == 20
    analysis = simulate(
        scenario, np.union1d(scenario.times(), passages), method="ali3p", step=2e-5, fast=True
    )
    errors = np.array(_a02_errors(analysis, reduced))
    measured = np.array(A02_SPEC)
    assert np.all((errors < FACTOR * measured) & (errors > measured / FACTOR)), errors
    assert errors[0] < 1e-8  # the bound on the energy
