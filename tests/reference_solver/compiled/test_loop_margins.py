"""The compiled time loop (compiled.loop.run, through compiled.path.run) at its margins: the mobility
decision at its margin, an assembly that lands near a singularity, grid
points that t_{k-1} + (t_k - t_{k-1}) does not reach in floating point, an iteration limit of zero,
a residual that overflows, two cam contacts in one program, and a residual whose largest row has
another scale than its column.

Expected values come from the hand-worked crank (tests.support.hand_crank: length 2 a pinned at its
end),
from dense algebra on the plain constraint system, and from the plain path."""

from __future__ import annotations

import dataclasses
import itertools
import math

import numpy as np
import pytest

import scenarios
from reference_solver.analysis import analyse, jumped
from reference_solver.compiled import path
from reference_solver.compiled.loop import (
    BRANCH_JUMP,
    EVENTS,
    NEAR_SINGULAR,
    NOT_CONVERGED,
    SIGN_CHANGE,
    UNVERIFIED,
)
from reference_solver.newton import NewtonSettings, newton
from reference_solver.system import ConstraintSystem
from scenarios import AbsoluteDriver, Constant, ConstantSpeed, Harmonic, Point, Prismatic, RollerCam, Scenario
from tests.support.hand_crank import A_HALF, AMPLITUDE, MEAN, OMEGA, crank_by_hand, crank_scenario
from tests.support.loop_checks import completed_run, dense_scaled_rcond_1, residual_reported_in_row_units


def _held_crank(x: float, theta_guess: float, length: float = 2 * A_HALF) -> Scenario:
    """The crank with its centre's x held at `x` (det C_q = -a sin(theta): singular at theta = 0),
    guessed on the pin's circle at `theta_guess`, with characteristic length `length`."""
    guess = (A_HALF * math.cos(theta_guess), A_HALF * math.sin(theta_guess), theta_guess)
    return dataclasses.replace(
        crank_scenario(guess),
        drivers=(AbsoluteDriver("drive", "crank", "x", Constant(x)),),
        characteristic_length=length,
    )


def _dense_norms(scenario: Scenario, q: np.ndarray) -> tuple[float, float, float, float]:
    """|A|_1, |A^-1|_1, |A|_inf, |A^-1|_inf of the scaled C_q at q, by dense inversion."""
    system = ConstraintSystem(scenario)
    a = system.scaled_jacobian(system.jacobian(q, 0.0))
    inverse = np.linalg.inv(a)
    return (
        float(np.linalg.norm(a, 1)),
        float(np.linalg.norm(inverse, 1)),
        float(np.linalg.norm(a, np.inf)),
        float(np.linalg.norm(inverse, np.inf)),
    )


MOBILITY_LENGTH = 0.01
"""L = a / 10: then |A^-1|_1 / |A^-1|_inf = 0.55 at the guesses below (measured), so an estimate in
the wrong norm moves sqrt(rcond_1 rcond_inf) by a factor 0.74 or 1.35."""


@pytest.mark.parametrize("factor", [0.86, 1.16])
def test_the_mobility_is_verified_above_its_margin_and_not_below(factor: float) -> None:
    """sqrt(rcond_1 rcond_inf) of the scaled C_q at the guess, computed by dense inversion, is linear
    in a small theta: guesses where it is 0.86 and 1.16 of MOBILITY_MARGIN. The kernel's estimates
    are exact on this 3 x 3 matrix (measured: it decides between 0.99 and 1.01 of the margin), so the
    first guess is not verified and the second runs (and assembles at x = a / 2, theta = pi / 3)."""
    probe = 1e-5
    one, one_inverse, inf, inf_inverse = _dense_norms(
        _held_crank(0.05, probe, MOBILITY_LENGTH),
        np.array([A_HALF * math.cos(probe), A_HALF * math.sin(probe), probe]),
    )
    per_radian = math.sqrt(1.0 / (one * one_inverse * inf * inf_inverse)) / probe
    assert 0.5 < one_inverse / inf_inverse < 0.6  # the norms differ: a wrong norm moves the value
    theta = factor * path.MOBILITY_MARGIN / per_radian
    scenario = _held_crank(0.05, theta, MOBILITY_LENGTH)
    q = np.array([A_HALF * math.cos(theta), A_HALF * math.sin(theta), theta])
    one, one_inverse, inf, inf_inverse = _dense_norms(scenario, q)
    assert math.sqrt(1.0 / (one * one_inverse * inf * inf_inverse)) == pytest.approx(
        factor * path.MOBILITY_MARGIN, rel=1e-4
    )
    run = path.run(scenario, np.array([0.0, 0.1]))
    if factor < 1:
        assert (run.event, run.index, run.analysis) == (EVENTS[UNVERIFIED], 0, None)
    else:
        assert run.event == "ok" and run.analysis is not None
        np.testing.assert_allclose(run.analysis.q[:, 2], math.pi / 3, rtol=0, atol=1e-12)


def test_an_assembly_that_lands_near_a_singularity_stops_at_the_first_grid_point() -> None:
    """x held at a cos(1e-7): the guess (theta = 0.5) is clearly regular, the assembled crank
    (theta = 1e-7) has a reciprocal condition number below the handover (dense: 1.7e-8 of the
    1-norm). The kernel reports it at grid point 0, where the plain path takes over, not before."""
    theta = 1e-7
    scenario = _held_crank(A_HALF * math.cos(theta), 0.5)
    system = ConstraintSystem(scenario)
    assembled = np.array([A_HALF * math.cos(theta), A_HALF * math.sin(theta), theta])
    assert dense_scaled_rcond_1(system, assembled, 0.0) < path.HANDOVER / 3  # the estimate overstates by < 3
    run = path.run(scenario, np.asarray(scenario.times()))
    assert (run.event, run.index, run.analysis) == (EVENTS[NEAR_SINGULAR], 0, None)


@pytest.mark.parametrize("grid", [[0.0, 0.2, 0.9], [0.9, 0.3, 0.0]], ids=["increasing", "decreasing"])
def test_a_grid_point_the_step_s_sum_misses_is_reached_by_one_newton_solve(grid: list[float]) -> None:
    """0.2 + (0.9 - 0.2) is 0.8999999999999999 and 0.9 + (0.3 - 0.9) is 0.29999999999999993 in
    floating point (checked below): each step still solves Newton at t_k itself from the predictor
    there, whose miss on the crank (steps of 0.2 s and more) needs one Newton step and a second to see
    it below the tolerance: at least two iterations at every point after the first, and the
    hand-worked motion."""
    times = np.asarray(grid)
    missed = [k for k in range(1, times.size) if times[k - 1] + (times[k] - times[k - 1]) != times[k]]
    assert missed
    result = completed_run(crank_scenario(), times)
    for level, expected in zip(("q", "qd", "qdd"), crank_by_hand(times), strict=True):
        np.testing.assert_allclose(getattr(result, level), expected, rtol=0, atol=1e-12, err_msg=level)
    assert result.iterations[0] == 0 and np.all(result.iterations[1:] >= 2)


def test_no_newton_iteration_allowed_fails_at_the_first_grid_point() -> None:
    """max_iterations 0: Newton may not take the step that confirms the assembled configuration at
    grid point 0 (the assembly's own limit and damping are for the assembly only)."""
    scenario = crank_scenario()
    run = path.run(scenario, np.asarray(scenario.times()), 1e-12, 0)
    assert (run.event, run.index, run.analysis) == (EVENTS[NOT_CONVERGED], 0, None)


def test_a_residual_that_overflows_is_a_newton_failure() -> None:
    """The crank turned at 1e200 rad/s: at t = 0 its acceleration (a theta'^2) overflows, so the
    predictor of the next point is infinite, and so is the residual there: Newton fails at index 1,
    not a configuration accepted or a crash."""
    scenario = dataclasses.replace(
        crank_scenario(), drivers=(AbsoluteDriver("drive", "crank", "theta", ConstantSpeed(0.5, 1e200)),)
    )
    with np.errstate(all="ignore"):  # uncompiled, numpy warns of the overflow
        run = path.run(scenario, np.array([0.0, 0.5, 1.0]))
    assert (run.event, run.index, run.analysis) == (EVENTS[NOT_CONVERGED], 1, None)


def _two_followers() -> Scenario:
    """cam_roller with a second roller follower guided along y below the cam (11 coordinates: three
    bodies and two contact angles): the kernel's profile points for two contacts."""
    base = scenarios.build("cam_roller")
    cam, follower = base.bodies
    contact = next(j for j in base.joints if isinstance(j, RollerCam))
    below = dataclasses.replace(follower, name="below", guess=(0.0, -follower.guess[1], 0.0))
    guide = Prismatic("guide_below", Point("below", (0.0, 0.0)), Point("ground", (0.0, 0.0)), (0.0, 1.0), 0.0)
    second = dataclasses.replace(
        contact, name="contact_below", centre=Point("below", (0.0, 0.0)), phi_guess=-math.pi / 2
    )
    return dataclasses.replace(
        base, bodies=(cam, follower, below), joints=(*base.joints, guide, second), steps=40
    )


def test_two_cam_contacts_in_the_kernel_give_the_plain_answer() -> None:
    scenario = _two_followers()
    grid = np.asarray(scenario.times())
    result = completed_run(scenario, grid)
    plain = analyse(scenario, compiled=False)
    for level in ("q", "qd", "qdd"):
        np.testing.assert_allclose(
            getattr(result, level), getattr(plain, level), rtol=0, atol=1e-10, err_msg=level
        )
    assert np.ptp(result.q[:, 4]) > 0.01 and np.ptp(result.q[:, 7]) > 0.01  # both followers move


def test_a_loose_tolerance_s_residual_is_in_row_units_where_rows_and_columns_differ() -> None:
    """The four-bar with L = 5 m (its links are centimetres): the rows of a revolute (in L) sit at
    the indices of angle columns (scale 1) too, so a residual divided by the column scales would be
    5 times the row-scaled one there. At tolerance 1e-3 the reported residual is max |C| / L^power at
    the reported q (plain rows)."""
    scenario = dataclasses.replace(scenarios.build("four_bar"), characteristic_length=5.0)
    system = ConstraintSystem(scenario)
    assert np.any(system.row_scales != system.column_scales)
    residual_reported_in_row_units(scenario, 1e-12)


def test_time_steps_take_newton_s_full_step_even_where_it_raises_the_residual() -> None:
    """The crank with x = 0.09 cos(3 t) (a = 0.1: theta = acos(x / a), near the fold theta = 0 at
    t = 0) in steps of 0.4 s: from the predictor at t = 1.2 Newton's full step raises the scaled
    residual (checked below with the plain rows at the hand-worked state of t = 0.8). Only the assembly
    damps (halves) a step; the time steps take the full step, as the plain path's Newton does: the
    same iteration counts as the plain path (measured [0, 5, 4, 8, 5, 5]) and the hand-worked motion."""
    scenario = dataclasses.replace(
        crank_scenario(),
        drivers=(AbsoluteDriver("drive", "crank", "x", Harmonic(0.0, 0.09, 3.0)),),
        t_end=2.0,
        steps=5,
    )
    system = ConstraintSystem(scenario)
    grid = np.asarray(scenario.times())
    f, df, ddf = 0.09 * np.cos(3 * grid), -0.27 * np.sin(3 * grid), -0.81 * np.cos(3 * grid)
    theta = np.arccos(f / A_HALF)
    c, s = np.cos(theta), np.sin(theta)
    thd = -df / (A_HALF * s)
    thdd = -(ddf + A_HALF * c * thd**2) / (A_HALF * s)
    q = np.stack([f, A_HALF * s, theta], axis=1)
    qd = np.stack([df, A_HALF * c * thd, thd], axis=1)
    qdd = np.stack([ddf, A_HALF * (c * thdd - s * thd**2), thdd], axis=1)

    def scaled(x: np.ndarray, t: float) -> float:
        return float(np.max(np.abs(system.residual(x, t) / system.row_scales)))

    h, t = grid[3] - grid[2], grid[3]
    predicted = q[2] + h * qd[2] + 0.5 * h**2 * qdd[2]
    full = predicted - np.linalg.solve(system.jacobian(predicted, t), system.residual(predicted, t))
    assert scaled(full, t) > scaled(predicted, t)

    result = completed_run(scenario, grid)
    plain = analyse(scenario, compiled=False)
    np.testing.assert_array_equal(result.iterations, plain.iterations)
    for level, expected in zip(("q", "qd", "qdd"), (q, qd, qdd), strict=True):
        np.testing.assert_allclose(getattr(result, level), expected, rtol=0, atol=1e-11, err_msg=level)


def _x_crank_state(amplitude: float, t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """q, q', q'' of the crank whose centre's x follows amplitude cos(3 t), worked by hand (as in
    test_a_crank_driven_at_its_centre_s_x_runs_in_the_kernel_and_moves_as_worked_by_hand)."""
    f, df, ddf = (
        amplitude * math.cos(3 * t),
        -3 * amplitude * math.sin(3 * t),
        -9 * amplitude * math.cos(3 * t),
    )
    theta = math.acos(f / A_HALF)
    c, s = math.cos(theta), math.sin(theta)
    thd = -df / (A_HALF * s)
    thdd = -(ddf + A_HALF * c * thd**2) / (A_HALF * s)
    return (
        np.array([f, A_HALF * s, theta]),
        np.array([df, A_HALF * c * thd, thd]),
        np.array([ddf, A_HALF * (c * thdd - s * thd**2), thdd]),
    )


def _first_step_leaves_its_branch(
    scenario: Scenario, state: tuple[np.ndarray, np.ndarray, np.ndarray], t0: float, h: float
) -> bool:
    """Whether the plain path's rule (analysis.jumped: the correction to the predictor, in column
    scales, above half the predictor's reach) says a step of h from the hand-worked `state` at t0
    leaves its branch, after plain Newton from the predictor; asserts that the kernel, on the grid
    (t0, t0 + h), hands over at index 1 exactly then."""
    system = ConstraintSystem(scenario)
    q, qd, qdd = state
    predicted = q + h * qd + 0.5 * h * h * qdd
    solved = newton(system, predicted, t0 + h, NewtonSettings(1e-12, 1e-12, 25))
    assert solved.converged
    left = jumped(system, qd, qdd, h, predicted, solved.q)
    run = path.run(scenario, np.array([t0, t0 + h]))
    assert (run.event == EVENTS[BRANCH_JUMP]) == left, (t0, h)
    assert run.index == 1 or not left
    return left


@pytest.mark.parametrize("length", [0.2, 0.01, 3.0])
def test_the_kernel_s_first_step_leaves_its_branch_where_the_plain_rule_says(length: float) -> None:
    """The crank with x = A cos(3 t), A = 0.09 and 0.099 m (a = 0.1: near its fold theta = 0 at t = 0),
    characteristic length L: one step of h from t0 (the grid's first step, k = 1). Measured: 3 to 6 of
    the 32 steps per L leave the branch (corrections 10 to 850 against reaches 4.6 to 625), the
    others converge near their predictor."""
    jumps = 0
    for amplitude, t0, h in itertools.product(
        (0.09, 0.099), (0.0, 0.3), (0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.8, 1.0)
    ):
        scenario = dataclasses.replace(
            crank_scenario(),
            drivers=(AbsoluteDriver("drive", "crank", "x", Harmonic(0.0, amplitude, 3.0)),),
            characteristic_length=length,
        )
        jumps += _first_step_leaves_its_branch(scenario, _x_crank_state(amplitude, t0), t0, h)
    assert 3 <= jumps <= 10


def test_a_coarse_step_of_a_small_swing_counts_as_leaving_its_branch_too() -> None:
    """The rule on a smooth path: the crank swung by theta = 0.5 + 0.05 cos(3 t), from t0 = pi / 6
    (theta'' = 0 there), in one step of h. The predictor misses by O(h^3) against a reach O(h): at
    h = 0.7 and 0.9 the correction (0.06, 0.11, below 0.5 in any unit) exceeds half the reach
    (0.105, 0.135; measured), and the kernel hands the step over; at 0.3 and 0.5 it does not."""
    scenario = dataclasses.replace(
        crank_scenario(), drivers=(AbsoluteDriver("drive", "crank", "theta", Harmonic(0.5, 0.05, 3.0)),)
    )
    t0 = math.pi / 6
    f, df, ddf = 0.5 + 0.05 * math.cos(3 * t0), -0.15 * math.sin(3 * t0), -0.45 * math.cos(3 * t0)
    c, s = math.cos(f), math.sin(f)
    state = (
        np.array([A_HALF * c, A_HALF * s, f]),
        np.array([-A_HALF * s * df, A_HALF * c * df, df]),
        np.array([-A_HALF * (c * df**2 + s * ddf), A_HALF * (c * ddf - s * df**2), ddf]),
    )
    left = [_first_step_leaves_its_branch(scenario, state, t0, h) for h in (0.3, 0.5, 0.7, 0.9)]
    assert left == [False, False, True, True]


def test_halved_steps_of_a_spline_cam_give_the_plain_answer() -> None:
    """The spline cam in two steps of half a revolution with two Newton iterations allowed: each step
    is retaken in halves, whose intermediate rates read the spline's profile too; the kernel's motion
    is the plain path's under the same settings."""
    scenario = scenarios.build("cam_roller/spline")
    grid = np.asarray(scenario.times(steps=2))
    result = completed_run(scenario, grid, max_iterations=2)
    plain = analyse(scenario, grid, max_iterations=2, compiled=False)
    for level in ("q", "qd", "qdd"):
        np.testing.assert_allclose(
            getattr(result, level), getattr(plain, level), rtol=0, atol=1e-10, err_msg=level
        )
    assert np.all(result.iterations <= 2)


def test_halved_steps_on_a_microsecond_grid_follow_the_motion() -> None:
    """The crank's motion a million times faster (omega = 3e6 rad/s) on the coarse grid of
    test_steps_newton_cannot_take_at_once_are_retaken_in_halves scaled to microseconds: the same
    halved steps, whose smallest allowed half is relative to the grid's times (1e-12 of them), so
    they still reach every point; the positions are the hand-worked ones at t * 1e6, the rates those
    times 1e6 and 1e12."""
    scenario = dataclasses.replace(
        crank_scenario(),
        drivers=(AbsoluteDriver("drive", "crank", "theta", Harmonic(MEAN, AMPLITUDE, OMEGA * 1e6)),),
    )
    grid = np.linspace(0.0, 1.0, 6)
    result = completed_run(scenario, grid * 1e-6, max_iterations=2)
    q, qd, qdd = crank_by_hand(grid)
    np.testing.assert_allclose(result.q, q, rtol=0, atol=1e-12)
    np.testing.assert_allclose(result.qd, qd * 1e6, rtol=0, atol=1e-12 * 1e6)
    np.testing.assert_allclose(result.qdd, qdd * 1e12, rtol=0, atol=1e-12 * 1e12)


def test_a_first_step_onto_the_other_branch_changes_the_sign_of_det_c_q() -> None:
    """The crank with x = 0.09 cos(3 t) in one step of 0.6 s from t = 0: plain Newton from the
    predictor converges at theta < 0, across the fold theta = 0 where det C_q = -a sin(theta) changes
    sign, by less than the rule's half reach (measured 2.2 against 6.7), so the step does not count
    as leaving its branch: the kernel reports the sign change at index 1."""
    scenario = dataclasses.replace(
        crank_scenario(), drivers=(AbsoluteDriver("drive", "crank", "x", Harmonic(0.0, 0.09, 3.0)),)
    )
    system = ConstraintSystem(scenario)
    q, qd, qdd = _x_crank_state(0.09, 0.0)
    h = 0.6
    predicted = q + h * qd + 0.5 * h * h * qdd
    solved = newton(system, predicted, h, NewtonSettings(1e-12, 1e-12, 25))
    assert solved.converged and math.sin(q[2]) > 0 > math.sin(solved.q[2])
    assert not jumped(system, qd, qdd, h, predicted, solved.q)
    run = path.run(scenario, np.array([0.0, h]))
    assert (run.event, run.index, run.analysis) == (EVENTS[SIGN_CHANGE], 1, None)
