"""ALI3-P's compiled step (fast.ali3p_kernel) where its tests did not reach (written for its mutation
pass, docs/mutation.md, session 10): a step that ends next to A02's singular position, where Newton
continues through the Schur complement, against the trapezoidal equations solved independently on
the parallelogram branch and the exact M-orthogonal projections of the rates at the step's q.

A02 with one loop (crank, coupler, rocker, links of 1 m and 1 kg): on the parallelogram branch the
crank and the rocker turn together, theta, and the coupler translates. At theta = 0 every link lies
on the x axis and C_q loses a rank: the rocker may turn apart from the crank. A step ending next to
it, from rates that put the rocker 1e-7 rad off the crank's turn, is slow for the augmented
Lagrangian (it contracts by 1/(1 + PENALTY s^2) per iteration along the rocker's own turn, s about
1e-5 here): the plain step stops at its stalled update, 1.6e-8 rad off the branch (measured)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

import scenarios
from reference_solver.compiled_system import constraint_system
from reference_solver.dynamics.ali3p import Ali3p, StepState
from reference_solver.dynamics.compiled_ali3p import CompiledAli3p, ali3p_stepper
from reference_solver.dynamics.loads import Loads
from reference_solver.dynamics.mass import mass_diagonal
from reference_solver.system import ConstraintSystem

H = 1e-3
G = 9.81
INERTIA = 2 / 3 + 1
"""Of the one-loop chain about the crank's angle: crank and rocker (1/3 each about their pivots),
the coupler translating at their tips' speed (1)."""
WEIGHT = G * (1 / 2 + 1 / 2 + 1)
"""The chain's potential energy per unit of sin(theta): crank and rocker centres at 1/2, coupler at 1."""
ENERGY = 0.5 * INERTIA + WEIGHT
"""Released at theta = pi/2 with the crank turning at -1 rad/s (n_four_bar's start)."""


def _branch(theta: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The parallelogram branch at crank angle theta, the coordinates in the layout's order (crank,
    coupler_1, rocker_1): q, dq/dtheta and d2q/dtheta2. Crank centre 0.5 e(theta), coupler centre
    (1/2, 0) + e(theta) at angle 0, rocker centre (1, 0) + 0.5 e(theta)."""
    e = np.array([math.cos(theta), math.sin(theta)])
    n = np.array([-e[1], e[0]])

    def link(base: float, reach: float, turns: float) -> tuple[list[float], list[float], list[float]]:
        return (
            [base + reach * e[0], reach * e[1], turns * theta],
            [reach * n[0], reach * n[1], turns],
            [-reach * e[0], -reach * e[1], 0.0],
        )

    parts = [link(0.0, 0.5, 1.0), link(0.5, 1.0, 0.0), link(1.0, 0.5, 1.0)]
    q, dq, d2q = (np.concatenate([p[k] for p in parts]) for k in range(3))
    return q, dq, d2q


def _m_projection(jac: np.ndarray, mass: np.ndarray, rates: np.ndarray, target: np.ndarray) -> np.ndarray:
    """The M-orthogonal projection of rates onto jac x = target, by the SVD of jac M^-1/2 (jac has
    full row rank here, its smallest singular value about 1e-5 of its largest)."""
    root = np.sqrt(mass)
    scaled = jac / root
    y = root * rates
    y -= np.linalg.pinv(scaled, rcond=1e-14) @ (scaled @ y - target)
    return y / root


def _start(loops_rate: float) -> tuple[StepState, np.ndarray]:
    """A state on the branch a step before theta = 0 (crank turning down, its energy ENERGY), its
    rocker's rate off by `loops_rate`; and the trapezoidal rule's qhat = q + h q' + h^2/4 q''."""
    rate0 = -math.sqrt(2 * ENERGY / INERTIA)  # at theta = 0
    theta = -rate0 * H + WEIGHT / INERTIA * H * H / 2
    rate = -math.sqrt(2 * (ENERGY - WEIGHT * math.sin(theta)) / INERTIA)
    accel = -WEIGHT / INERTIA * math.cos(theta)
    q, dq, d2q = _branch(theta)
    qd, qdd = dq * rate, dq * accel + d2q * rate * rate
    qd[-1] += loops_rate
    state = StepState(0.0, q, qd, qdd, np.zeros(8), np.zeros((8, 9)))
    return state, q + H * qd + H * H / 4 * qdd


def _trapezoidal_on_the_branch(qhat: np.ndarray, mass: np.ndarray, gravity: np.ndarray) -> float:
    """The crank angle at which the trapezoidal equations M 4/h^2 (q - qhat) + C_q^T mu = Q_e hold on
    the parallelogram branch: their component along its tangent, dq/dtheta . (M 4/h^2 (q - qhat) -
    Q_e) = 0 (C_q dq/dtheta = 0 there), solved by bracketing."""

    def along(theta: float) -> float:
        q, dq, _ = _branch(theta)
        return float(dq @ (4 / (H * H) * mass * (q - qhat) - gravity))

    guess = float(qhat[2])
    return float(brentq(along, guess - 1e-3, guess + 1e-3, xtol=1e-20, rtol=8.9e-16))


def _one_loop() -> tuple[CompiledAli3p, Ali3p, ConstraintSystem, np.ndarray, Loads]:
    scenario = scenarios.build("n_four_bar", overrides={"loops": 1})
    fast, plain = constraint_system(scenario), constraint_system(scenario, fast=False)
    mass = mass_diagonal(scenario, plain.layout)
    compiled = ali3p_stepper(fast, mass, Loads(scenario, fast.layout, mass), H)
    assert isinstance(compiled, CompiledAli3p)
    loads = Loads(scenario, plain.layout, mass)
    return compiled, Ali3p(plain, mass, loads, H), plain, mass, loads


@pytest.mark.parametrize("off", [1e-4, -1e-4])
def test_a_step_ending_next_to_the_singular_position_goes_through_the_schur_complement(off: float) -> None:
    """Positions: the trapezoidal equations' solution on the branch, to 5.6e-12 and 5.8e-12
    (measured, compiled and as Python), where the plain step stops 1.6e-8 off; rates: the exact
    M-orthogonal projections at the step's q, q' onto C_q q' = 0 (measured 3.6e-16 of the largest
    trapezoidal rate, 5 rad/s) and q'' onto C_q q'' = Q_d (3.6e-12 and 4.6e-12 of the largest
    trapezoidal acceleration); the multipliers (1.4e3 here): C_q^T (alpha C + lambda*) = Q_e -
    M q''_trapezoidal to 0.067 and 0.089 N, alpha C being alpha (4e14) times C's round-off (0.044 N)."""
    compiled, plain_step, plain, mass, loads = _one_loop()
    start, qhat = _start(off)
    end = compiled.step(start)
    assert compiled.slow_steps >= 1
    exact, _, _ = _branch(_trapezoidal_on_the_branch(qhat, mass, loads.gravity))
    assert np.max(np.abs(end.q - exact)) < 1.5e-11
    assert np.max(np.abs(plain_step.step(start).q - exact)) > 1e-9  # the stall the Schur path ends
    jac = plain.jacobian(end.q, end.t)
    trapezoidal = 2 / H * (end.q - start.q) - start.qd
    rates = _m_projection(jac, mass, trapezoidal, np.zeros(8))
    assert np.max(np.abs(end.qd - rates)) < 1e-15 * np.max(np.abs(trapezoidal))
    accel = 4 / (H * H) * (end.q - qhat)
    projected = _m_projection(jac, mass, accel, plain.q_d(end.q, end.qd, end.t))
    assert np.max(np.abs(end.qdd - projected)) < 1.2e-11 * np.max(np.abs(accel))
    c = plain.residual(end.q, end.t)
    balance = jac.T @ (compiled.alpha * c + end.multipliers) - (loads.gravity - mass * accel)
    assert np.max(np.abs(balance)) < 0.25
