"""ALI3-P's compiled step (dynamics.compiled_ali3p, compiled.ali3p_kernel) against the plain step
(dynamics.ali3p on the plain constraints) on random states, its row-stored C_q against finite
differences of C, and its banded Cholesky solve against a dense solve of W built independently.

The index-3 rates are q' = 2/h q + ..., q'' = 4/h^2 q + ...: round-off in q reaches them multiplied
by 2/h and 4/h^2, so they are compared as h q' / 2 and h^2 q'' / 4, on the scale of q."""

from __future__ import annotations

import numpy as np
import pytest

from reference_solver.compiled.evaluate import evaluate
from reference_solver.compiled.program import K_SLOT_COL, K_WIDTH, WIDTH
from reference_solver.compiled_system import constraint_system
from reference_solver.dynamics.ali3p import Ali3p, StepState
from reference_solver.dynamics.compiled_ali3p import CompiledAli3p, ali3p_stepper
from reference_solver.dynamics.loads import Loads
from reference_solver.dynamics.mass import mass_diagonal
from scenarios import load
from tests.support.compiled_dynamics import both, random_states

NO_FORCES = ["compound_pendulum", "four_bar_gravity", "n_four_bar"]
H = 1e-3


def _steppers(name: str, h: float) -> tuple[CompiledAli3p, Ali3p]:
    scenario = load(name)
    compiled_system, plain = constraint_system(scenario), constraint_system(scenario, compiled=False)
    mass = mass_diagonal(scenario, plain.layout)
    compiled = ali3p_stepper(compiled_system, mass, Loads(scenario, compiled_system.layout, mass), h)
    assert isinstance(compiled, CompiledAli3p)
    return compiled, Ali3p(plain, mass, Loads(scenario, plain.layout, mass), h)


def _states(name: str, count: int) -> list[StepState]:
    """Consistent states (positions on the manifold, rates and accelerations with their
    multipliers) at random independent coordinates and rates near the scenario's start."""
    _, partitioned, start = both(name)
    out = []
    for t, y in random_states(partitioned, start, count, seed=7):
        s = partitioned.state(t, y)
        out.append(StepState(s.t, s.q, s.qd, s.qdd, s.lam, s.jac))
    return out


@pytest.mark.parametrize("name", NO_FORCES)
def test_one_step_equals_the_plain_step(name: str) -> None:
    compiled, plain = _steppers(name, H)
    scale = plain.system.layout.length_scale
    for state in _states(name, 4):
        a, b = compiled.step(state), plain.step(state)
        assert a.t == pytest.approx(b.t, abs=1e-15)
        for x, y, factor in ((a.q, b.q, 1.0), (a.qd, b.qd, H / 2), (a.qdd, b.qdd, H * H / 4)):
            assert np.max(np.abs(x - y)) * factor < 1e-12 * scale
        # lambda* carries alpha times C's round-off (dynamics.ali3p.PENALTY); the multipliers at
        # the state, recomputed as the output gives them (an augmented Lagrangian projection, whose
        # multipliers carry alpha times the round-off of C_q x), agree to that: measured 7.2e-9
        # relative on compound_pendulum, 1.4e-9 and 1.2e-10 on the others (positions: 1.6e-14)
        load = plain.loads(b.q, b.qd, b.t).generalized
        lam_a, lam_b = compiled.multipliers(a, load), plain.multipliers(b, load)
        assert np.max(np.abs(lam_a - lam_b)) < 2.5e-8 * np.max(np.abs(lam_b))
        assert np.max(np.abs(plain.system.residual(a.q, a.t) / plain.system.row_scales)) < 1e-13


@pytest.mark.parametrize("name", NO_FORCES)
def test_row_stored_jacobian_matches_finite_differences_of_c(name: str) -> None:
    compiled, _ = _steppers(name, H)
    ints, reals = compiled.arguments[:2]
    state = _states(name, 1)[0]
    store, work, scratch, us = compiled.arguments[5], *compiled.arguments[-3:]
    m, n = compiled.m, compiled.n
    c, q_d = np.zeros(m), np.zeros(m)

    def residual(q: np.ndarray) -> np.ndarray:
        evaluate(ints, reals, q, np.zeros(n), state.t, c, q_d, store, work, scratch, us)
        return c.copy()

    residual(state.q)
    jac = np.zeros((m, n))
    for r in range(m):
        for s in range(ints[r, K_WIDTH]):
            jac[r, ints[r, K_SLOT_COL + s]] += store[r * WIDTH + s]
    step = 1e-6 * compiled.system.column_scales
    numeric = np.zeros((m, n))
    for j in range(n):
        e = np.zeros(n)
        e[j] = step[j]
        numeric[:, j] = (residual(state.q + e) - residual(state.q - e)) / (2 * step[j])
    assert np.max(np.abs(jac - numeric)) < 1e-8


@pytest.mark.parametrize("name", NO_FORCES)
def test_banded_cholesky_solves_w(name: str) -> None:
    compiled, plain = _steppers(name, H)
    state = _states(name, 1)[0]
    compiled.step(state)  # factors W at this step's predictor and fixes the penalties
    rng = np.random.default_rng(3)
    rhs = rng.standard_normal(compiled.n)
    x = compiled.solve(rhs)
    # W is factored at the step's predictor
    predictor = state.q + H * state.qd + H * H / 2 * state.qdd
    jac = plain.system.jacobian(predictor, state.t + H)
    w = np.diag(compiled.mass) + H * H / 4 * jac.T @ (compiled.alpha[:, None] * jac)
    assert np.max(np.abs(w @ x - rhs)) < 1e-12 * np.max(np.abs(rhs)) * np.linalg.norm(w, 1)
