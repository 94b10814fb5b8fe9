"""The compiled time loop (compiled.loop.run) where a Newton that converged leaves C_q exactly singular,
and where a halved step ends within a factor of the handover: branches of `run` that no catalogue
scene reaches.

The scene: a rod pinned at the ground origin (its frame origin) with a slider on the rod's x axis,
the slider's x driven by f(t) = A (cos(w t) - 1) - floor and its y held at 0. Worked by hand: the
rod and the slider stay at theta = 0, the rod's origin at (0, 0), the slider at (f(t), 0). The
prismatic joint's normal row, (-sin theta_rod, cos theta_rod) . (r_rod - r_slider), has the
derivative f(t) in theta_rod (the slider's distance along the rod): where f = 0 (t = 0 without a
floor) the rod's two angle columns are +1 and -1 in the angle row and zero elsewhere, so C_q is
exactly singular (rank 5 of 6), and every quantity that decides it is a linear row solved exactly
(f(0) = A (cos 0 - 1) = 0 in floating point).

The predictor's miss at t = 0 from t = -h, by Taylor's series of the cosine:
    f(0) - (f(-h) + h f'(-h) + h^2 / 2 f''(-h)) = -A w^4 h^4 / 8 + O(h^6),
and from -h to +h: f(h) - (f(-h) + 2 h f'(-h) + 2 h^2 f''(-h)) = -(2 / 3) A w^4 h^4 + O(h^6).
One Newton iteration sets x_slider to f(t) exactly (a linear row of coefficient 1); the step it took
is the predictor's miss, so Newton confirms convergence at the next evaluation only if that miss is
below the tolerance 1e-12 (L = 1 m: every scale is 1)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from reference_solver.compiled import path
from reference_solver.compiled.loop import EVENTS, NEAR_SINGULAR
from reference_solver.system import ConstraintSystem
from scenarios import GROUND, AbsoluteDriver, Body, Constant, Harmonic, Point, Prismatic, Revolute
from scenarios.scenario import Scenario

A, W = 16.0, 1.0
TOLERANCE = 1e-12


def _slider_through_the_pin(floor: float = 0.0) -> Scenario:
    return Scenario(
        family="slider_through_pin",
        variant="default",
        bodies=(Body("rod", (0.0, 0.0, 0.0), length=1.0), Body("slider", (-1.0, 0.0, 0.0), length=0.1)),
        joints=(
            Revolute("pin", Point("rod", (0.0, 0.0)), Point(GROUND, (0.0, 0.0))),
            Prismatic("slide", Point("rod", (0.0, 0.0)), Point("slider", (0.0, 0.0))),
        ),
        drivers=(
            AbsoluteDriver("sx", "slider", "x", Harmonic(-A - floor, A, W)),
            AbsoluteDriver("sy", "slider", "y", Constant(0.0)),
        ),
        t_end=1.0,
        steps=2,
        characteristic_length=1.0,
    )


def _q(t: float, floor: float = 0.0) -> np.ndarray:
    """The hand-worked configuration: (rod x, y, theta, slider x, y, theta)."""
    return np.array([0.0, 0.0, 0.0, A * (math.cos(W * t) - 1.0) - floor, 0.0, 0.0])


def _scaled_c_q(scenario: Scenario, q: np.ndarray) -> np.ndarray:
    system = ConstraintSystem(scenario)
    assert np.all(system.row_scales == 1.0) and np.all(system.column_scales == 1.0)
    return system.scaled_jacobian(system.jacobian(q, 0.0))


def _rcond(a: np.ndarray, norm: float) -> float:
    """1 / (|A|_1 |A^-1|_norm), by dense inversion: the 1-norm reciprocal condition number for
    norm = 1, and for norm = inf what a 1-norm |A| with the infinity norm of the inverse gives."""
    return float(1.0 / (np.linalg.norm(a, 1) * np.linalg.norm(np.linalg.inv(a), norm)))


def test_the_scene_is_singular_exactly_where_the_slider_reaches_the_pin() -> None:
    """Dense algebra on the plain rows: rank 5 at t = 0, the slider on the pin. At a distance d from
    the pin, C_q^-1 = v w^T / d + O(1) with v the rod's and slider's angles (1 each) and w the rows
    normal - pin.y + sy.y, so |C_q^-1|_1 = |v|_1 |w|_inf / d = 2 / d and |C_q^-1|_inf = 3 / d; |C_q|_1
    = 2 (the pin.y and normal rows in y_rod's column): the 1-norm rcond is d / 4, the wrong norm's
    d / 6."""
    scenario = _slider_through_the_pin()
    assert np.linalg.matrix_rank(_scaled_c_q(scenario, _q(0.0))) == 5
    assert _q(0.0)[3] == 0.0
    for distance in (1e-6, 1e-4):
        q = np.array([0.0, 0.0, 0.0, -distance, 0.0, 0.0])
        a = _scaled_c_q(scenario, q)
        assert _rcond(a, 1) == pytest.approx(distance / 4, rel=10 * distance)
        assert _rcond(a, np.inf) == pytest.approx(distance / 6, rel=10 * distance)


def test_a_grid_point_newton_confirms_on_an_exactly_singular_c_q_is_near_singular() -> None:
    """Grid (-h, 0) with h = sqrt(2 u / (A w^2)), the slider u = 4e-6 m from the pin at -h (dense
    rcond there far above the handover): the predictor misses f(0) by A w^4 h^4 / 8 = 5e-13, below
    the tolerance, so Newton confirms at t = 0 with the factors of the exactly singular C_q (a zero
    pivot). The kernel reports the near-singular C_q at index 1 (a mutant taking rc = 1 for a zero
    pivot, `run` 523, reported a sign change)."""
    scenario = _slider_through_the_pin()
    u = 4e-6
    h = math.sqrt(2 * u / (A * W * W))
    miss = A * W**4 * h**4 / 8
    assert miss == pytest.approx(5e-13)
    assert _rcond(_scaled_c_q(scenario, _q(-h)), 1) > 3 * path.HANDOVER
    run = path.run(scenario, np.array([-h, 0.0]))
    assert (run.event, run.index, run.analysis) == (EVENTS[NEAR_SINGULAR], 1, None)


D = (3.75e-12 / A) ** 0.25 / W
"""Half the grid step: the predictor misses by (2 / 3) A w^4 D^4 = 2.5e-12 from -D to D, by A w^4 D^4 / 8 =
4.7e-13 from -D to 0."""


def test_a_halved_step_newton_confirms_on_an_exactly_singular_c_q_is_near_singular() -> None:
    """Grid (-D, D) with one Newton iteration allowed: the predictor misses f(D) by 2.5e-12 (above
    the tolerance: the full step is not confirmed) and f(0) by 4.7e-13 (below it), so the first half
    step ends at t = 0 exactly (-D + D), where C_q is exactly singular: near-singular at index 1.
    A mutant taking rc = 1 there (`run` 419) went on with rates solved on the singular factors. With
    25 iterations the full step converges at D and the run completes (the halving is what stops)."""
    scenario = _slider_through_the_pin()
    full, half = 2 / 3 * A * W**4 * D**4, A * W**4 * D**4 / 8
    assert full == pytest.approx(2.5e-12) and half == pytest.approx(4.6875e-13)
    assert -D + D == 0.0
    run = path.run(scenario, np.array([-D, D]), TOLERANCE, 1)
    assert (run.event, run.index, run.analysis) == (EVENTS[NEAR_SINGULAR], 1, None)
    run = path.run(scenario, np.array([-D, D]), TOLERANCE, 25)
    assert run.event == "ok" and run.analysis is not None
    np.testing.assert_allclose(run.analysis.q, [_q(-D), _q(D)], rtol=0, atol=1e-15)


def test_a_halved_step_just_above_the_handover_goes_on() -> None:
    """The slider kept `floor` from the pin (its closest approach at t = 0), with floor set so that the
    dense 1-norm reciprocal condition number there is 1.2 times the handover: the halved step that
    ends at t = 0 (as above, one Newton iteration) is regular enough, and the run completes with the
    hand-worked motion. The inverse's infinity norm is 1.5 times its 1-norm here (dense), so a halved
    step's estimate taken in the wrong norm (`run` 416) falls to 0.8 of the handover and stops."""
    floor = 4 * 1.2 * path.HANDOVER  # rcond_1 = floor / 4 (above)
    scenario = _slider_through_the_pin(floor)
    a = _scaled_c_q(scenario, _q(0.0, floor))
    assert _rcond(a, 1) == pytest.approx(1.2 * path.HANDOVER, rel=1e-5)
    assert _rcond(a, np.inf) == pytest.approx(0.8 * path.HANDOVER, rel=1e-5)
    run = path.run(scenario, np.array([-D, D]), TOLERANCE, 1)
    assert run.event == "ok" and run.analysis is not None
    np.testing.assert_allclose(run.analysis.q, [_q(-D, floor), _q(D, floor)], rtol=0, atol=1e-15)
