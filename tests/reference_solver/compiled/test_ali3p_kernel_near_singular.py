"""ALI3-P's compiled step (compiled.ali3p_kernel) next to a singular position: a step that ends next to
A02's singular position, where Newton
continues through the Schur complement, against the trapezoidal equations solved independently on
the parallelogram branch and the exact M-orthogonal projections of the rates at the step's q.

A02 with one loop (tests.support.one_loop: crank, coupler, rocker, links of 1 m and 1 kg): on the
parallelogram branch the
crank and the rocker turn together, theta, and the coupler translates. At theta = 0 every link lies
on the x axis and C_q loses a rank: the rocker may turn apart from the crank. A step ending next to
it, from rates that put the rocker 1e-7 rad off the crank's turn, is slow for the augmented
Lagrangian (it contracts by 1/(1 + PENALTY s^2) per iteration along the rocker's own turn, s about
1e-5 here): the plain step stops at its stalled update, off the branch."""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any

import numpy as np
import pytest

import scenarios
from reference_solver.compiled import ali3p_kernel as kernel
from reference_solver.compiled.dense_lu import lu_solve
from reference_solver.compiled.program import K_SLOT_COL, WIDTH
from reference_solver.compiled_system import constraint_system
from reference_solver.dynamics.ali3p import PENALTY, Ali3p, StepState
from reference_solver.dynamics.compiled_ali3p import CompiledAli3p, ali3p_stepper
from reference_solver.dynamics.loads import Loads
from reference_solver.dynamics.mass import mass_diagonal
from reference_solver.errors import ConvergenceError
from scenarios import Point
from scenarios.drivers import AbsoluteDriver
from scenarios.joints import RevoluteRevolute
from scenarios.motions import ConstantSpeed
from tests.support.a02_chain import steps_alike_in_metres_and_kilometres
from tests.support.ali3p_rod import THETA0, compiled_stepper_at_rest, rod_stepper, swinging_rod
from tests.support.one_loop import (
    G,
    H,
    kernel_problem,
    one_loop_steppers,
    parallelogram_branch,
    projected_exactly,
    rates_are_the_projections,
    state_before_passage,
    trapezoidal_on_the_branch,
)
from tests.support.row_stores import dense_jacobian, random_row_store


@pytest.mark.parametrize("off", [1e-4, -1e-4])
def test_a_step_ending_next_to_the_singular_position_goes_through_the_schur_complement(off: float) -> None:
    """Positions: the trapezoidal equations' solution on the branch, to 5.6e-12 and 5.8e-12
    (measured, compiled and as Python), where the plain step stops 1.6e-8 off; rates: the exact
    M-orthogonal projections at the step's q, q' onto C_q q' = 0 (measured 3.6e-16 of the largest
    trapezoidal rate, 5 rad/s) and q'' onto C_q q'' = Q_d (3.6e-12 and 4.6e-12 of the largest
    trapezoidal acceleration); the multipliers (1.4e3 here): C_q^T (alpha C + lambda*) = Q_e -
    M q''_trapezoidal to 0.067 and 0.089 N, alpha C being alpha (4e14) times C's round-off (0.044 N)."""
    compiled, plain_step, plain, mass, loads = one_loop_steppers()
    start, qhat = state_before_passage(off)
    end, power, work = compiled.run(start, 1, np.zeros(3), np.zeros(3))
    assert compiled.slow_steps >= 1
    assert power.tolist() == [0.0, 0.0, 0.0] and work.tolist() == [0.0, 0.0, 0.0]  # no driver
    exact, _, _ = parallelogram_branch(trapezoidal_on_the_branch(qhat, mass, loads.gravity))
    assert np.max(np.abs(end.q - exact)) < 1.5e-11
    assert np.max(np.abs(plain_step.step(start).q - exact)) > 1e-9  # the stall the Schur path ends
    jac, accel = rates_are_the_projections(plain, mass, start, qhat, end)
    c = plain.residual(end.q, end.t)
    balance = jac.T @ (compiled.alpha * c + end.multipliers) - (loads.gravity - mass * accel)
    assert np.max(np.abs(balance)) < 0.25


def _schur_of(p: dict[str, Any]) -> None:
    kernel._schur(
        p["ints"], p["store"], p["vec"], p["sizes"], p["band"], p["weight"], p["schur"], p["pivots"]
    )


@pytest.mark.parametrize(("seed", "n", "m"), [(0, 12, 7), (1, 15, 12), (3, 9, 4)])
def test_schur_factors_the_dense_schur_complement(seed: int, n: int, m: int) -> None:
    """S = weight C_q W^-1 C_q^T (W and C_q dense), by its solves: S x = b for random b; the slow
    count goes up by one."""
    p = kernel_problem(seed, n, m, 1.0)
    _schur_of(p)
    jac = p["jac"]
    dense = p["weight"] * jac @ np.linalg.solve(p["w_dense"], jac.T)
    assert p["sizes"][kernel.S_SLOW] == 6
    for _ in range(3):
        b = p["rng"].standard_normal(m)
        x = b.copy()
        lu_solve(p["schur"], m, p["pivots"], x)
        np.testing.assert_allclose(dense @ x, b, rtol=0, atol=1e-11 * np.abs(b).max())


@pytest.mark.parametrize(("seed", "n", "m"), [(0, 12, 7), (1, 15, 12), (3, 9, 4)])
def test_the_kkt_correction_solves_the_dense_kkt_system(seed: int, n: int, m: int) -> None:
    """With move = W^-1 f: [W, weight C_q^T; C_q, 0] [dx; dmu] = -[f; gap] solved densely; the kernel
    leaves -dx in move and adds dmu to the multipliers."""
    p = kernel_problem(seed, n, m, 1.0)
    _schur_of(p)
    rng, jac, weight = p["rng"], p["jac"], p["weight"]
    f, gap, start = rng.standard_normal(n), rng.standard_normal(m), rng.standard_normal(m)
    kkt = np.block([[p["w_dense"], weight * jac.T], [jac, np.zeros((m, m))]])
    exact = np.linalg.solve(kkt, -np.concatenate([f, gap]))
    move, multiplier = np.linalg.solve(p["w_dense"], f), start.copy()
    kernel._kkt_correction(
        p["ints"],
        p["store"],
        p["vec"],
        p["sizes"],
        p["band"],
        weight,
        p["schur"],
        p["pivots"],
        move,
        gap.copy(),
        multiplier,
    )
    np.testing.assert_allclose(move, -exact[:n], rtol=0, atol=1e-10 * np.abs(exact[:n]).max())
    np.testing.assert_allclose(multiplier, start + exact[n:], rtol=0, atol=1e-10 * np.abs(exact[n:]).max())


def _project_with_the_kernel(
    p: dict[str, Any], rates: np.ndarray, target: np.ndarray, slow: bool
) -> np.ndarray:
    x = rates.copy()
    kernel._project(
        p["ints"],
        p["store"],
        p["vec"],
        p["sizes"],
        p["band"],
        p["weight"],
        p["schur"],
        p["pivots"],
        x,
        target.copy(),
        slow,
    )
    return x


@pytest.mark.parametrize(("seed", "n", "m"), [(0, 12, 7), (1, 15, 12), (3, 9, 4)])
@pytest.mark.parametrize("size", [1e3, 1e-3])
def test_a_projection_through_the_schur_complement_is_exact(seed: int, n: int, m: int, size: float) -> None:
    """With penalties that leave the augmented Lagrangian slow (alpha at 1 times the rows' inertia,
    C_q M^-1 C_q^T conditioned up to 1e6), the projection through the Schur complement is the exact
    M-orthogonal projection (measured to 4.6e-12 of the largest rate on the worst conditioned)."""
    p = kernel_problem(seed, n, m, 1.0)
    _schur_of(p)
    rng = p["rng"]
    rates, target = size * rng.standard_normal(n), size * rng.standard_normal(m)
    exact = projected_exactly(p, rates, target)
    got = _project_with_the_kernel(p, rates, target, True)
    np.testing.assert_allclose(got, exact, rtol=0, atol=1.5e-11 * np.abs(exact).max())


def _augmented_lagrangian(p: dict[str, Any], rates: np.ndarray, target: np.ndarray) -> list[np.ndarray]:
    """The iterates of the projection's augmented Lagrangian (dynamics.projection), densely:
    W x_k = M rates + weight C_q^T (alpha target - sigma_k), sigma_{k+1} = sigma_k + alpha (C_q x_k -
    target), sigma_0 = 0; x_0 = rates."""
    jac, alpha, weight = p["jac"], p["alpha"], p["weight"]
    sigma, out = np.zeros(target.size), [rates]
    for _ in range(kernel.PROJECTION_STEPS):
        x = np.linalg.solve(p["w_dense"], p["mass"] * rates + weight * jac.T @ (alpha * target - sigma))
        sigma = sigma + alpha * (jac @ x - target)
        out.append(x)
    return out


def _stop(iterates: list[np.ndarray]) -> int:
    """Where the kernel's rule stops (compiled.ali3p_kernel, PROJECTION_STALLED's docstring and _project's):
    at a move below SETTLED relative to the rates' largest, or at one that no longer halves when it
    is below PROJECTION_STALLED or no move before it shrank by SLOW_START."""
    scale = np.abs(iterates[0]).max()
    previous, best = math.inf, math.inf
    for k in range(1, len(iterates)):
        size = np.abs(iterates[k] - iterates[k - 1]).max() / scale
        if size <= kernel.SETTLED:
            return k
        if size > 0.5 * previous and (size < kernel.PROJECTION_STALLED or best >= kernel.SLOW_START):
            return k
        if previous < math.inf:
            best = min(best, size / previous)
        previous = size
    return len(iterates) - 1


@pytest.mark.parametrize(
    ("seed", "n", "m", "gain", "stop"),
    [(0, 12, 7, 30.0, 3), (3, 9, 4, 3.0, 4), (1, 15, 12, 1.0, 5), (0, 12, 7, 1e5, 0)],
)
@pytest.mark.parametrize("size", [1.0, 1e3, 1e-17])
def test_a_projection_stops_at_the_iterate_its_rule_picks(
    seed: int, n: int, m: int, gain: float, stop: int, size: float
) -> None:
    """The augmented Lagrangian alone: slow ones (moves shrinking by 0.74 to 0.84 once their fast
    parts are gone) stop at the third to fifth iterate, short of the projection, as the kernel
    means them to (see _project); a fast one (penalties 1e5 times the rows' inertia) reaches the
    exact projection and stalls at its round-off. Rates of size 1 to 1e3 and 1e-17: the rule is
    relative to the rates' largest."""
    p = kernel_problem(seed, n, m, gain)
    rng = p["rng"]
    rates, target = size * rng.standard_normal(n), size * rng.standard_normal(m)
    iterates = _augmented_lagrangian(p, rates, target)
    got = _project_with_the_kernel(p, rates, target, False)
    if stop:
        assert _stop(iterates) == stop
        expected = iterates[stop]
        np.testing.assert_allclose(got, expected, rtol=0, atol=1e-12 * np.abs(expected).max())
    else:  # converged: where round-off stalls it is round-off's choice
        exact = projected_exactly(p, rates, target)
        np.testing.assert_allclose(got, exact, rtol=0, atol=1e-13 * np.abs(exact).max())


@pytest.mark.parametrize(("seed", "scale"), [(0, 10.0), (1, 1e-3)])
@pytest.mark.parametrize("zero_rows", [(2,), (0, 1, 2, 3, 4, 5, 6)])
def test_the_penalties_are_dynamics_ali3p_s(seed: int, scale: float, zero_rows: tuple[int, ...]) -> None:
    """alpha_r = PENALTY 4/h^2 / max((C_q M^-1 C_q^T)_rr, 1e-12 of the largest, or of 1 where every
    row is zero), as dynamics.ali3p fixes them; rows of C_q scaled by 10 and 1e-3 (the largest
    diagonal away from 1), one row or every row without a used slot. The kernel sums the squares of
    a row's slots: a program never holds a column twice in a row (equation.Equation's columns are
    those of distinct bodies), so the random stores here hold none either."""
    n, m, h = 12, 7, 2e-3
    rng = np.random.default_rng(seed)
    ints, store = random_row_store(rng, m, n, 4)
    store *= scale
    for r in range(m):  # no column twice in a row, as in every program (Equation's columns are unique)
        cols = ints[r, K_SLOT_COL : K_SLOT_COL + WIDTH]
        for k in range(1, WIDTH):
            if cols[k] in cols[:k]:
                cols[k] = -1
    for r in zero_rows:
        ints[r, K_SLOT_COL : K_SLOT_COL + WIDTH] = -1
    jac = dense_jacobian(ints, store, m, n)
    mass = rng.uniform(0.5, 2.0, n)
    inertia = np.einsum("ij,j,ij->i", jac, 1 / mass, jac)
    typical = float(np.max(inertia)) or 1.0
    expected = PENALTY * 4 / (h * h) / np.maximum(inertia, 1e-12 * typical)
    vec = np.full((kernel.VECTORS, n), np.nan)
    vec[kernel.MASS] = mass
    sizes = np.zeros(8, np.int64)
    sizes[[kernel.S_N, kernel.S_M]] = n, m
    params = np.zeros(5)
    params[kernel.P_H], params[kernel.P_PENALTY] = h, PENALTY
    kernel._penalties(ints, store, vec, sizes, params)
    np.testing.assert_allclose(vec[kernel.ALPHA, :m], expected, rtol=1e-14)


def test_a_step_newton_cannot_finish_takes_every_allowed_iteration() -> None:
    """The rod of test_compiled_ali3p_run held at a fixed angle while its centre is driven along x:
    no position meets both, so Newton runs its NEWTON_STEPS iterations (one constraint evaluation
    each) and stops, no more and no fewer."""
    rod = swinging_rod()
    slide = AbsoluteDriver("slide", "rod", "x", ConstantSpeed(0.5 * np.cos(THETA0), 5.0))
    turn = AbsoluteDriver("turn", "rod", "theta", ConstantSpeed(THETA0, 0.0))
    scenario = replace(rod, drivers=(turn, slide))
    stepper, s = compiled_stepper_at_rest(scenario, H)
    with pytest.raises(ConvergenceError):
        stepper.step(s)
    assert stepper.sizes[kernel.S_ITERATIONS] == kernel.NEWTON_STEPS == 60
    assert stepper.evaluations == 60


def test_the_penalties_are_fixed_at_the_first_factorization_with_one_row() -> None:
    """A body swinging on a massless link to the ground (one row, whose C_q M^-1 C_q^T changes as it
    swings, the link pinned off the body's centre): alpha stays the first step's formula,
    PENALTY 4/h^2 / (C_q M^-1 C_q^T) at that step's predictor, through 100 later steps (over which
    that diagonal changes by more than 1 %)."""
    h = 1e-3
    body = scenarios.Body("body", (1.0, 0.0, 0.0), mass=2.0, inertia=0.2, length=1.0)
    link = RevoluteRevolute("link", Point("ground", (0.0, 0.0)), Point("body", (-0.4, 0.3)), 0.6**0.5)
    scenario = scenarios.Scenario(
        "swing", "default", (body,), (link,), (), 1.0, 10, 1.0, gravity=(0.0, -G), analysis="dynamic"
    )
    system = constraint_system(scenario)
    mass = mass_diagonal(scenario, system.layout)
    stepper = ali3p_stepper(system, mass, Loads(scenario, system.layout, mass), h)
    assert isinstance(stepper, CompiledAli3p) and stepper.m == 1
    q = np.array([0.6**0.5 + 0.4, -0.3, 0.0])
    s = StepState(0.0, q, np.zeros(3), np.zeros(3), np.zeros(1), np.zeros((1, 3)))  # released at rest

    def inertia(q: np.ndarray, t: float) -> float:
        return float(system.jacobian(q, t)[0] ** 2 @ (1 / mass))

    first = PENALTY * 4 / (h * h) / inertia(s.q + h * s.qd, h)
    s, _, _ = stepper.run(s, 1, np.zeros(3), np.zeros(3))
    assert stepper.alpha[0] == pytest.approx(first, rel=1e-12)
    end, _, _ = stepper.run(s, 100, np.zeros(3), np.zeros(3))
    assert abs(inertia(end.q, end.t) / inertia(s.q, s.t) - 1) > 1e-2
    assert stepper.alpha[0] == pytest.approx(first, rel=1e-12)


def test_the_compiled_step_is_the_same_in_any_unit_of_length() -> None:
    """As dynamics.ali3p's (test_ali3p.py): the compound double pendulum with links of 1 m under
    g = 9.81 and of 1 km under g = 9.81e3 takes as many Newton iterations at every step, and gives
    the same angles and lengths a thousand times (Newton measures its updates over the column
    scales and C over the row scales)."""

    def compiled(scenario: scenarios.Scenario, h: float) -> tuple[Ali3p, StepState]:
        stepper, _, start = rod_stepper(scenario, True, h)
        assert isinstance(stepper, CompiledAli3p)
        return stepper, start

    steps_alike_in_metres_and_kilometres(compiled)


def test_a_newton_iteration_that_overflows_is_refused_as_the_plain_step_refuses_it() -> None:
    """One-loop A02 a step before it passes 3e-3 rad from the horizontal, its multipliers lambda*
    put 1e8 off along C_q's smallest singular direction: Newton overflows (updates of 1e270 in the
    plain step). The plain step refuses it; so must the compiled one, whose largest update and
    residual were maxima that skip NaN (max(0.0, nan) is 0.0), so it returned NaN positions as a
    converged step."""
    compiled, plain_step, plain, _, _ = one_loop_steppers()
    start, _ = state_before_passage(0.0)
    q, dq, _ = parallelogram_branch(start.q[2] + 3e-3)
    first = compiled.step(replace(start, q=q, qd=dq * start.qd[2]))
    smallest = np.linalg.svd(plain.jacobian(first.q, first.t))[0][:, -1]
    off = replace(first, multipliers=first.multipliers + 1e8 * smallest)
    with pytest.raises(ConvergenceError), np.errstate(all="ignore"):
        plain_step.step(off)
    with pytest.raises(
        ConvergenceError, match=r"^n_four_bar: ALI3-P's Newton iteration did not converge at t=0\.002$"
    ):
        compiled.step(off)


@pytest.mark.parametrize(("angle", "off"), [(3e-3, 1e4), (1e-3, 1e6)])
def test_a_stall_at_newton_s_second_update_goes_through_the_schur_complement(
    angle: float, off: float
) -> None:
    """A step from a state on the branch (the compiled step's own, `angle` before the horizontal)
    whose lambda* is `off` along C_q's smallest singular direction: the predictor is good, so
    Newton's first update is small and its second, the augmented Lagrangian's slow multiplier
    correction along that direction, shrinks by less than SLOW. The stall counts from the second
    update on: Newton goes through the Schur complement there and ends in 4 and 5 iterations
    (measured; checking from the third update on, it takes 6 without the Schur complement), at the
    trapezoidal equations' solution on the branch (measured 4.6e-15 and 3.5e-14 rad)."""
    compiled, _, plain, mass, loads = one_loop_steppers()
    start, _ = state_before_passage(0.0)
    q, dq, _ = parallelogram_branch(start.q[2] + angle)
    first = compiled.step(replace(start, q=q, qd=dq * start.qd[2]))
    smallest = np.linalg.svd(plain.jacobian(first.q, first.t))[0][:, -1]
    end = compiled.step(replace(first, multipliers=first.multipliers + off * smallest))
    assert compiled.slow_steps == 1
    assert end.iterations <= (4 if off < 1e5 else 5)
    qhat = first.q + H * first.qd + H * H / 4 * first.qdd
    exact, _, _ = parallelogram_branch(trapezoidal_on_the_branch(qhat, mass, loads.gravity))
    assert np.max(np.abs(end.q - exact)) < 1e-13
