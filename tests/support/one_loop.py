"""A02 with one loop (crank, coupler, rocker, links of 1 m and 1 kg) for the tests of ALI3-P's compiled
step next to the singular position: its parallelogram branch, the trapezoidal equations solved on it
independently, the exact M-orthogonal projections of the rates, and random problems for the kernel's
linear algebra."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from scipy.optimize import brentq

import scenarios
from reference_solver.compiled import ali3p_kernel as kernel
from reference_solver.compiled.ali3p_matrix import factor
from reference_solver.compiled_system import constraint_system
from reference_solver.dynamics.ali3p import Ali3p, StepState
from reference_solver.dynamics.compiled_ali3p import CompiledAli3p, ali3p_stepper
from reference_solver.dynamics.loads import Loads
from reference_solver.dynamics.mass import mass_diagonal
from reference_solver.system import ConstraintSystem
from tests.support.row_stores import dense_jacobian, random_row_store, store_bandwidth

H = 1e-3
G = 9.81
INERTIA = 2 / 3 + 1
"""Of the one-loop chain about the crank's angle: crank and rocker (1/3 each about their pivots),
the coupler translating at their tips' speed (1)."""
WEIGHT = G * (1 / 2 + 1 / 2 + 1)
"""The chain's potential energy per unit of sin(theta): crank and rocker centres at 1/2, coupler at 1."""
ENERGY = 0.5 * INERTIA + WEIGHT
"""Released at theta = pi/2 with the crank turning at -1 rad/s (n_four_bar's start)."""


def parallelogram_branch(theta: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
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


def state_before_passage(loops_rate: float) -> tuple[StepState, np.ndarray]:
    """A state on the branch a step before theta = 0 (crank turning down, its energy ENERGY), its
    rocker's rate off by `loops_rate`; and the trapezoidal rule's qhat = q + h q' + h^2/4 q''."""
    rate0 = -math.sqrt(2 * ENERGY / INERTIA)  # at theta = 0
    theta = -rate0 * H + WEIGHT / INERTIA * H * H / 2
    rate = -math.sqrt(2 * (ENERGY - WEIGHT * math.sin(theta)) / INERTIA)
    accel = -WEIGHT / INERTIA * math.cos(theta)
    q, dq, d2q = parallelogram_branch(theta)
    qd, qdd = dq * rate, dq * accel + d2q * rate * rate
    qd[-1] += loops_rate
    state = StepState(0.0, q, qd, qdd, np.zeros(8), np.zeros((8, 9)))
    return state, q + H * qd + H * H / 4 * qdd


def trapezoidal_on_the_branch(qhat: np.ndarray, mass: np.ndarray, gravity: np.ndarray) -> float:
    """The crank angle at which the trapezoidal equations M 4/h^2 (q - qhat) + C_q^T mu = Q_e hold on
    the parallelogram branch: their component along its tangent, dq/dtheta . (M 4/h^2 (q - qhat) -
    Q_e) = 0 (C_q dq/dtheta = 0 there), solved by bracketing."""

    def along(theta: float) -> float:
        q, dq, _ = parallelogram_branch(theta)
        return float(dq @ (4 / (H * H) * mass * (q - qhat) - gravity))

    guess = float(qhat[2])
    return float(brentq(along, guess - 1e-3, guess + 1e-3, xtol=1e-20, rtol=8.9e-16))


def one_loop_steppers() -> tuple[CompiledAli3p, Ali3p, ConstraintSystem, np.ndarray, Loads]:
    scenario = scenarios.build("n_four_bar", overrides={"loops": 1})
    compiled_system, plain = constraint_system(scenario), constraint_system(scenario, compiled=False)
    mass = mass_diagonal(scenario, plain.layout)
    compiled = ali3p_stepper(compiled_system, mass, Loads(scenario, compiled_system.layout, mass), H)
    assert isinstance(compiled, CompiledAli3p)
    loads = Loads(scenario, plain.layout, mass)
    return compiled, Ali3p(plain, mass, loads, H), plain, mass, loads


def rates_are_the_projections(
    plain: ConstraintSystem, mass: np.ndarray, start: StepState, qhat: np.ndarray, end: StepState
) -> tuple[np.ndarray, np.ndarray]:
    """Asserts a step's q' and q'' are the exact M-orthogonal projections at its q of the
    trapezoidal rate onto C_q q' = 0 (to 1e-15 of the largest) and of the trapezoidal acceleration
    onto C_q q'' = Q_d (to 1.2e-11); returns C_q and that acceleration."""
    jac = plain.jacobian(end.q, end.t)
    trapezoidal = 2 / H * (end.q - start.q) - start.qd
    rates = _m_projection(jac, mass, trapezoidal, np.zeros(8))
    assert np.max(np.abs(end.qd - rates)) < 1e-15 * np.max(np.abs(trapezoidal))
    accel = 4 / (H * H) * (end.q - qhat)
    projected = _m_projection(jac, mass, accel, plain.q_d(end.q, end.qd, end.t))
    assert np.max(np.abs(end.qdd - projected)) < 1.2e-11 * np.max(np.abs(accel))
    return jac, accel


def kernel_problem(seed: int, n: int, m: int, gain: float) -> dict[str, Any]:
    """A random row store of full row rank (m < n, from test_fast_ali3p_matrix), masses, penalties
    alpha_r = gain / (C_q M^-1 C_q^T)_rr, W = M + weight C_q^T diag(alpha) C_q factored by
    ali3p_matrix.factor, and the kernel's arrays around them (the slow count at 5)."""
    rng = np.random.default_rng(seed)
    ints, store = random_row_store(rng, m, n, 4)
    jac = dense_jacobian(ints, store, m, n)
    assert np.linalg.matrix_rank(jac) == m
    w, weight = store_bandwidth(ints, m), 0.25e-6
    mass = rng.uniform(0.5, 2.0, n)
    alpha = gain / weight / np.einsum("ij,j,ij->i", jac, 1 / mass, jac)
    vec = np.full((kernel.VECTORS, n), np.nan)  # scratch rows start as garbage
    vec[kernel.MASS], vec[kernel.ALPHA, :m] = mass, alpha
    sizes = np.zeros(8, np.int64)
    sizes[[kernel.S_N, kernel.S_M, kernel.S_W, kernel.S_SLOW]] = n, m, w, 5
    band = np.zeros((n, w + 1))
    assert factor(ints, store, mass, vec[kernel.ALPHA], n, m, w, band, weight)
    big = np.diag(mass) + weight * jac.T @ (alpha[:, None] * jac)
    schur, pivots = np.full((m, m), np.nan), np.zeros(m, np.int64)
    return dict(
        ints=ints,
        store=store,
        jac=jac,
        vec=vec,
        sizes=sizes,
        band=band,
        weight=weight,
        mass=mass,
        alpha=alpha,
        w_dense=big,
        schur=schur,
        pivots=pivots,
        rng=rng,
        n=n,
        m=m,
    )


def projected_exactly(p: dict[str, Any], rates: np.ndarray, target: np.ndarray) -> np.ndarray:
    """The M-orthogonal projection onto C_q x = target, densely."""
    jac, inverse = p["jac"], 1 / p["mass"]
    gram = jac @ (inverse[:, None] * jac.T)
    return rates - inverse * (jac.T @ np.linalg.solve(gram, jac @ rates - target))
