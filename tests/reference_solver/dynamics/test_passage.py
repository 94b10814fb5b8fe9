"""Singular passages on ALI3-P's grid (dynamics.passage, dynamics.ali3p_schedule): the smallest scaled
singular value of C_q against a dense SVD, the watch's linear prediction of its zero, and the A02
chain (10 loops) through its first passage at three phases of the singular instant in its step,
with the watch (careful steps and the step placed across the instant) and without (equal steps),
against the chain's own one-degree-of-freedom solution (test_ali3p._chain)."""

from __future__ import annotations

import math

import numpy as np
import pytest

import scenarios
from reference_solver.compiled_system import constraint_system
from reference_solver.dynamics import ali3p_grid, ali3p_schedule, simulate
from reference_solver.dynamics.ali3p import PENALTY
from reference_solver.dynamics.mass import mass_diagonal
from reference_solver.dynamics.passage import CAREFUL, FAR, FIRST, NEAR, Watch, smallest_singular_value
from reference_solver.errors import ConvergenceError
from tests.support.a02_chain import FACTOR, a02_chain, a02_errors
from tests.support.passage_spies import compiled_schedule, fail_when_careful


def _dense(jac: np.ndarray, mass: np.ndarray) -> np.ndarray:
    """The singular values of D^-1/2 C_q M^-1/2 by a dense SVD (D: the rows' inertias)."""
    scaled = jac / np.sqrt(mass)
    scaled = scaled / np.linalg.norm(scaled, axis=1)[:, None]
    return np.linalg.svd(scaled, compute_uv=False)


def test_the_smallest_singular_value_is_the_dense_svd_s() -> None:
    """On a 3-loop chain at a perturbed state (banded Gram matrix), on a small dense matrix (the
    dense path) and with a row repeated (rank one less: the smallest the rank keeps)."""
    scenario = scenarios.build("n_four_bar", overrides={"loops": 3})
    system = constraint_system(scenario)
    mass = mass_diagonal(scenario, system.layout)
    rng = np.random.default_rng(5)
    q = system.layout.initial_guess(scenario) + 0.1 * rng.standard_normal(system.unknowns)
    jac = system.jacobian(q, 0.0)
    rank = jac.shape[0]
    assert smallest_singular_value(jac, mass, rank) == pytest.approx(_dense(jac, mass)[-1], rel=1e-9)
    dense = rng.standard_normal((4, 6))
    weights = rng.uniform(0.5, 2.0, 6)
    assert smallest_singular_value(dense, weights, 4) == pytest.approx(_dense(dense, weights)[-1], rel=1e-9)
    repeated = np.vstack([jac, jac[:1]])
    assert smallest_singular_value(repeated, mass, rank) == pytest.approx(
        _dense(repeated, mass)[rank - 1], rel=1e-9
    )
    assert smallest_singular_value(jac, mass, 0) == math.inf


def test_the_watch_predicts_the_zero_of_a_falling_line() -> None:
    """Two readings on s = 2 (1 - t) predict t* = 1 and the slope 2; a rising pair predicts nothing;
    the steps to the next reading: FIRST after one reading, FAR when s rises, half the steps to the
    careful region (at least NEAR, at most FAR) when it falls, NEAR inside it."""
    watch = Watch(np.ones(3), 1)
    h = 1e-3
    watch.readings = [(0.25, 1.5)]
    assert watch.zero() is None and watch.steps_to_check(h) == FIRST
    watch.readings = [(0.25, 1.5), (0.5, 1.0)]
    zero, slope = watch.zero() or (math.nan, math.nan)
    assert zero == pytest.approx(1.0, abs=1e-15) and slope == pytest.approx(2.0, abs=1e-15)
    below = math.sqrt(CAREFUL / PENALTY)
    assert watch.steps_to_check(h) == int((1.0 - below) / 2 / h / 2)  # 500 steps to go: 249
    assert watch.steps_to_check(1e-5) == FAR and watch.steps_to_check(1.0) == NEAR
    watch.readings = [(0.5, 1.0), (0.25, 1.5)]
    assert watch.zero() is None and watch.steps_to_check(h) == FAR
    watch.readings = [(0.0, 1.0), (0.5, below / 2)]
    assert watch.careful and watch.steps_to_check(h) == NEAR
    watch.forget()
    assert watch.readings == [] and not watch.careful


CHAIN = {
    # steps over 0.77 s: (phase of the instant in its step, rockers at the passage with the watch,
    # and with equal steps), measured
    38506: (0.022, 4.84e-12, 1.15e-10),
    38500: (0.410, 8.95e-12, 1.10e-10),
    38491: (0.990, 1.73e-12, 1.14e-10),
}


@pytest.mark.parametrize("count", sorted(CHAIN))
def test_a_chain_s_rockers_stay_on_the_crank_through_a_placed_passage(
    count: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    """10 loops through their first passage (t* = 0.7203 s): with the watch the step across the
    instant is placed (once) and the rockers at the passage stay near 1e-11 whatever its phase;
    with equal steps they are 1.1e-10 off at each phase. The energy and the crank are the same to
    their own accuracy either way (drift 3.7e-9 to 4.4e-9 of the kinetic energy, crank 1.2e-9)."""
    phase, watched, equal = CHAIN[count]
    scenario, grid, reduced = a02_chain(10, 0.77)
    h = 0.77 / count
    assert reduced.t_events[0][0] / h % 1 == pytest.approx(phase, abs=1e-3)  # type: ignore[attr-defined]
    placed: list[float] = []
    place = ali3p_schedule.Schedule._place

    def spied(self: ali3p_schedule.Schedule) -> None:
        placed.append(self.zero)
        place(self)

    monkeypatch.setattr(ali3p_schedule.Schedule, "_place", spied)
    errors = a02_errors(simulate(scenario, grid, method="ali3p", step=h * (1 + 1e-9), compiled=True), reduced)
    assert placed == [pytest.approx(reduced.t_events[0][0], abs=0.01 * h)]  # type: ignore[attr-defined]
    assert watched / FACTOR < errors[1] < FACTOR * watched
    assert errors[0] < 5e-9 and errors[2] < 1.5e-9
    monkeypatch.setattr(ali3p_grid, "Watch", lambda mass, rank: None)
    plain = a02_errors(simulate(scenario, grid, method="ali3p", step=h * (1 + 1e-9), compiled=True), reduced)
    assert equal / FACTOR < plain[1] < FACTOR * equal
    assert plain[0] == pytest.approx(errors[0], rel=0.15) and plain[2] == pytest.approx(errors[2], rel=0.02)


def test_a_careful_step_that_fails_is_taken_again_without_care(monkeypatch: pytest.MonkeyPatch) -> None:
    """The schedule's step: a careful step that raises (a Schur complement next to an instant the
    watch did not predict) is taken again with the augmented Lagrangian alone, which gives the
    state an uncareful step gives; a step that fails without care still raises."""
    scenario = scenarios.build("n_four_bar", overrides={"loops": 2, "t_end": 0.01, "steps": 1})
    stepper, first, schedule = compiled_schedule(scenario)
    expected = stepper.step(first)
    fail_when_careful(monkeypatch, stepper, 0.001)
    schedule.advance(0.001)
    assert not stepper.careful and schedule.before is first
    np.testing.assert_array_equal(schedule.state.q, expected.q)
    monkeypatch.setattr(
        stepper, "run", lambda *args: (_ for _ in ()).throw(ConvergenceError("no", time=0.002))
    )
    with pytest.raises(ConvergenceError, match=r"^no$"):
        schedule.advance(0.002)
