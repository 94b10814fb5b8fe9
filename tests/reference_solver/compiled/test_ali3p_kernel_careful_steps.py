"""ALI3-P's compiled step (compiled.ali3p_kernel) in the careful steps of singular passages: a careful
step next to A02's singular position against the trapezoidal equations solved on the parallelogram
branch (tests.support.one_loop), and two failures the kernel must not pass on as results: a Schur
complement that is exactly singular, and a projection whose moves are not finite (its largest move
is a max(), which skips NaN, so a NaN move would read as settled)."""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np
import pytest

import scenarios
from reference_solver.compiled import ali3p_kernel as kernel
from reference_solver.compiled.ali3p_matrix import factor
from reference_solver.compiled.program import K_SLOT_COL, WIDTH
from reference_solver.compiled_system import constraint_system
from reference_solver.dynamics.ali3p import StepState
from reference_solver.dynamics.compiled_ali3p import CompiledAli3p, ali3p_stepper
from reference_solver.dynamics.loads import Loads
from reference_solver.dynamics.mass import mass_diagonal
from reference_solver.errors import ConvergenceError
from scenarios import Point
from scenarios.drivers import AbsoluteDriver
from scenarios.joints import RevoluteRevolute
from scenarios.motions import Harmonic
from tests.support import one_loop
from tests.support.ali3p_rod import THETA0, compiled_stepper_at_rest, swinging_rod
from tests.support.row_stores import dense_jacobian, random_row_store, store_bandwidth


@pytest.mark.parametrize("off", [1e-4, -1e-4])
def test_a_careful_step_next_to_the_singular_position_factors_s_once(off: float) -> None:
    """The step of test_fast_ali3p_kernel_mutants (ending about 1.2e-5 rad from the horizontal, the
    rocker's rate off the crank's by `off`), careful: Newton and both projections go through the
    Schur complement from the first iteration, so S is factored once (the augmented Lagrangian
    stalls along the rocker's own turn and factors it again at the stall if the first factorization
    is not used), in fewer Newton iterations than the same step without care (measured 5 and 3
    against 7 and 8), and the step ends at the trapezoidal equations' solution on the branch
    (measured 8.1e-13 and 5.8e-12 rad), q' at the exact M-orthogonal projection of the trapezoidal
    rates (1.8e-16 and 3.5e-16 of them), q'' at that of the trapezoidal accelerations onto
    C_q q'' = Q_d (5.4e-12 and 2.8e-12 of them)."""
    compiled, _, plain, mass, loads = one_loop.one_loop_steppers()
    start, qhat = one_loop.state_before_passage(off)
    uncareful = compiled.run(start, 1, np.zeros(3), np.zeros(3))[0].iterations
    compiled.careful = True
    end, _, _ = compiled.run(start, 1, np.zeros(3), np.zeros(3))
    assert compiled.slow_steps == 2  # one for each step: the uncareful one's at its stall
    assert end.iterations < uncareful
    exact, _, _ = one_loop.parallelogram_branch(one_loop.trapezoidal_on_the_branch(qhat, mass, loads.gravity))
    assert np.max(np.abs(end.q - exact)) < 1.5e-11
    one_loop.rates_are_the_projections(plain, mass, start, qhat, end)


def _schur_problem(zero_row: int | None) -> tuple[dict[str, Any], np.ndarray]:
    """A random 12 x 7 row store (test_fast_ali3p_matrix's generator), its row `zero_row` without a
    used slot, unit penalties; W factored. Returns the kernel's arguments and C_q densely."""
    n, m, weight = 12, 7, 0.25e-6
    rng = np.random.default_rng(0)
    ints, store = random_row_store(rng, m, n, 4)
    if zero_row is not None:
        ints[zero_row, K_SLOT_COL : K_SLOT_COL + WIDTH] = -1
    jac = dense_jacobian(ints, store, m, n)
    w = store_bandwidth(ints, m)
    vec = np.zeros((kernel.VECTORS, n))
    vec[kernel.MASS], vec[kernel.ALPHA, :m] = rng.uniform(0.5, 2.0, n), 1.0
    sizes = np.zeros(8, np.int64)
    sizes[[kernel.S_N, kernel.S_M, kernel.S_W]] = n, m, w
    band = np.zeros((n, w + 1))
    assert factor(ints, store, vec[kernel.MASS], vec[kernel.ALPHA], n, m, w, band, weight)
    arguments = dict(ints=ints, store=store, vec=vec, sizes=sizes, band=band, weight=weight)
    return arguments, jac


@pytest.mark.parametrize("zero_row", [None, 0, 3, 6])
def test_schur_reports_a_schur_complement_that_is_exactly_singular(zero_row: int | None) -> None:
    """A row of C_q that is zero makes that row and column of S = weight C_q W^-1 C_q^T zero, so its
    LU factorization meets an exactly zero pivot (lu_factor's flag), and its solves would divide by
    zero: _schur says so (False), and True for the full-rank store; the slow count goes up either
    way."""
    arguments, jac = _schur_problem(zero_row)
    assert np.linalg.matrix_rank(jac) == (7 if zero_row is None else 6)
    m = 7
    schur, pivots = np.zeros((m, m)), np.zeros(m, np.int64)
    a = arguments
    ok = kernel._schur(a["ints"], a["store"], a["vec"], a["sizes"], a["band"], a["weight"], schur, pivots)
    assert ok is (zero_row is None)
    assert a["sizes"][kernel.S_SLOW] == 1


def _tied() -> tuple[CompiledAli3p, StepState]:
    """A body tied to a ground point by a massless link of length 0 (C = |d|^2, whose C_q = 2 d^T
    vanishes where the points meet), at rest with the points together."""
    body = scenarios.Body("body", (0.3, 0.0, 0.0), mass=2.0, inertia=0.2, length=1.0)
    link = RevoluteRevolute("link", Point("ground", (0.3, 0.0)), Point("body", (0.0, 0.0)), 0.0)
    scenario = scenarios.Scenario(
        "tied", "default", (body,), (link,), (), 1.0, 10, 1.0, gravity=(0.0, -9.81), analysis="dynamic"
    )
    system = constraint_system(scenario)
    mass = mass_diagonal(scenario, system.layout)
    stepper = ali3p_stepper(system, mass, Loads(scenario, system.layout, mass), one_loop.H)
    assert isinstance(stepper, CompiledAli3p)
    q = np.array([0.3, 0.0, 0.0])
    assert not np.any(system.jacobian(q, 0.0))
    return stepper, StepState(0.0, q, np.zeros(3), np.zeros(3), np.zeros(1), np.zeros((1, 3)))


def test_a_careful_step_whose_schur_complement_is_singular_is_refused_as_such() -> None:
    """At the tied body's start C_q is zero, so the careful step's Schur complement is exactly zero:
    the step is refused naming it (the schedule then retakes it without care), not taken with factors
    that divide by zero (which ended in NaN updates and a 'did not converge')."""
    stepper, start = _tied()
    stepper.careful = True
    with pytest.raises(
        ConvergenceError,
        match=r"^tied: ALI3-P's Schur complement C_q W\^-1 C_q\^T is singular \(C_q lost rank\) at t=0\.001$",
    ) as caught:
        stepper.step(start)
    assert caught.value.time == pytest.approx(one_loop.H, abs=1e-18)
    stepper.careful = False
    with pytest.raises(
        ConvergenceError, match=r"^tied: ALI3-P's Newton iteration did not converge at t=0\.001$"
    ):
        stepper.step(start)


@pytest.mark.parametrize("slow", [False, True])
@pytest.mark.parametrize("bad", [np.nan, np.inf])
def test_a_projection_whose_moves_are_not_finite_says_so(slow: bool, bad: float) -> None:
    """_project onto a target with one entry NaN or infinite: its moves are not finite, which the
    largest move (a max(), skipping NaN) cannot tell from a settled projection; _project returns
    False. With every entry finite it returns True and the exact projection (through the Schur
    complement, checked densely)."""
    p = one_loop.kernel_problem(0, 12, 7, 1.0)
    kernel._schur(
        p["ints"], p["store"], p["vec"], p["sizes"], p["band"], p["weight"], p["schur"], p["pivots"]
    )
    rng = p["rng"]
    rates, target = rng.standard_normal(12), rng.standard_normal(7)
    common = (p["ints"], p["store"], p["vec"], p["sizes"], p["band"], p["weight"], p["schur"], p["pivots"])
    x = rates.copy()
    assert kernel._project(*common, x, target.copy(), True) is True
    np.testing.assert_allclose(
        x, one_loop.projected_exactly(p, rates, target), rtol=0, atol=1.5e-11 * np.abs(x).max()
    )
    broken = target.copy()
    broken[3] = bad
    x = rates.copy()
    assert kernel._project(*common, x, broken, slow) is False


def test_a_driver_whose_acceleration_overflows_is_refused_not_stepped() -> None:
    """The rod of test_compiled_ali3p_run turned by theta = THETA0 + 1e-300 cos(1e300 t): the angle
    and its rate (of order 1) are finite, its acceleration 1e-300 (1e300)^2 overflows, so the target
    of the q'' projection is infinite. The step is refused at its end (t = h), not returned as done
    with NaN accelerations."""
    turn = AbsoluteDriver("turn", "rod", "theta", Harmonic(THETA0, 1e-300, 1e300))
    scenario = replace(swinging_rod(), drivers=(turn,))
    stepper, start = compiled_stepper_at_rest(scenario, one_loop.H)
    with (
        pytest.raises(
            ConvergenceError,
            match=r"^rod: ALI3-P's projection of the rates gave non-finite rates at t=0\.001$",
        ),
        np.errstate(all="ignore"),
    ):
        stepper.step(start)
    assert stepper.params[kernel.P_T] == 0.0  # the failed step's start, as for Newton's failures
