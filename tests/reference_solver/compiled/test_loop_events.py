"""The compiled time loop (compiled.loop.run, through compiled.path.run) on mechanisms worked by hand, and
each of its events where the mechanism says it must happen.

The crank of test_analysis.py (length 2 a pinned at its end, theta = m + A cos(w t)) gives q, q', q''
by hand; the residual and the reciprocal condition number at each grid point are checked against
their definitions, computed here with the plain constraint system and dense algebra."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import scenarios
from reference_solver.compiled import path
from reference_solver.compiled.loop import (
    ASSEMBLY_FAILED,
    EVENTS,
    NEAR_SINGULAR,
    NOT_CONVERGED,
    SIGN_CHANGE,
    UNVERIFIED,
)
from reference_solver.system import ConstraintSystem
from scenarios import AbsoluteDriver, Constant, Harmonic
from tests.support.hand_crank import A_HALF, OMEGA, crank_by_hand, crank_scenario, unassembled_pair
from tests.support.loop_checks import completed_run, dense_scaled_rcond_1, residual_reported_in_row_units


def test_the_crank_s_motion_residual_and_conditioning_are_the_hand_worked_ones() -> None:
    """q, q', q'' to 1e-12; the residual reported at each point is max |C| / L^power at the reported
    q (computed with the plain rows); the conditioning is the 1-norm estimate, which can only
    overstate the reciprocal condition number, and on a 3 x 3 matrix stays within a factor 3 of it."""
    scenario = crank_scenario()
    system = ConstraintSystem(scenario)
    grid = np.asarray(scenario.times())
    result = completed_run(scenario, grid)
    for level, expected in zip(("q", "qd", "qdd"), crank_by_hand(grid), strict=True):
        np.testing.assert_allclose(getattr(result, level), expected, rtol=0, atol=1e-12, err_msg=level)
    assert result.iterations[0] == 0 and np.all(result.iterations[1:] >= 1)
    assert np.all(result.iterations[1:] <= 3)  # the predictor is second order: no step is retaken
    for k, t in enumerate(grid):
        miss = np.max(np.abs(system.residual(result.q[k], t) / system.row_scales))
        assert result.residual[k] == pytest.approx(miss, abs=1e-16)
        exact = dense_scaled_rcond_1(system, result.q[k], t)
        assert exact * (1 - 1e-12) <= result.rcond[k] <= 3 * exact, k


def test_a_grid_of_one_time_is_the_assembled_configuration_and_its_rates() -> None:
    result = completed_run(crank_scenario(), [0.3])
    for level, expected in zip(("q", "qd", "qdd"), crank_by_hand(np.array([0.3])), strict=True):
        np.testing.assert_allclose(getattr(result, level), expected, rtol=0, atol=1e-12, err_msg=level)
    assert list(result.iterations) == [0]


@pytest.mark.parametrize(
    "grid",
    [
        pytest.param(np.linspace(1.0, 0.0, 21), id="decreasing"),
        pytest.param(np.linspace(-1.0, 0.0, 21), id="negative times"),
        pytest.param(np.linspace(0.0, 1.0, 6), id="coarse"),
    ],
)
def test_steps_newton_cannot_take_at_once_are_retaken_in_halves(grid: np.ndarray) -> None:
    """Two Newton iterations allowed: some whole steps fail and are retaken in halved steps (the
    kernel's analysis._approach), forwards and backwards in time; the motion is still the hand-worked
    one, and no point reports more than the two iterations."""
    result = completed_run(crank_scenario(), grid, max_iterations=2)
    for level, expected in zip(("q", "qd", "qdd"), crank_by_hand(grid), strict=True):
        np.testing.assert_allclose(getattr(result, level), expected, rtol=0, atol=1e-12, err_msg=level)
    assert np.all(result.iterations <= 2)


def test_a_guess_where_c_q_is_singular_is_not_verified() -> None:
    """test_analysis._unassembled: at the guess C_q has two zero rows, so the kernel cannot verify the
    mobility and hands the run over at index 0."""
    system, _ = unassembled_pair()
    run = path.run(system.scenario, np.array([0.0, 1.0]))
    assert (run.event, run.index, run.analysis) == (EVENTS[UNVERIFIED], 0, None)


def _x_driven(motion: Harmonic | Constant):  # type: ignore[no-untyped-def]
    """The crank with its centre's x driven instead of its angle: its band has no subdiagonal (kl = 0),
    so the band store's first entry is a diagonal entry (the y row's y column)."""
    return dataclasses.replace(crank_scenario(), drivers=(AbsoluteDriver("drive", "crank", "x", motion),))


def test_a_crank_driven_at_its_centre_s_x_runs_in_the_kernel_and_moves_as_worked_by_hand() -> None:
    """x = f(t) = 0.05 cos(3 t) (within the pin's reach a = 0.1) on the branch of the guess (theta in
    (0, pi)): theta = acos(f / a), y = a sin(theta); from x = a cos(theta),
    theta' = -f' / (a sin(theta)), theta'' = -(f'' + a cos(theta) theta'^2) / (a sin(theta)),
    y' = a cos(theta) theta', y'' = a (cos(theta) theta'' - sin(theta) theta'^2).
    (A bug found by this test: compile_program left the store position of the slots off a row's pattern
    at 0, so the kernel wrote zeros over the band store's first entry, here the y row's diagonal: C_q
    was singular at the guess and every run was handed to the plain path.)"""
    scenario = _x_driven(Harmonic(0.0, 0.05, OMEGA))
    grid = np.asarray(scenario.times())
    result = completed_run(scenario, grid)
    f, df, ddf = (
        0.05 * np.cos(OMEGA * grid),
        -0.05 * OMEGA * np.sin(OMEGA * grid),
        -0.05 * OMEGA**2 * np.cos(OMEGA * grid),
    )
    th = np.arccos(f / A_HALF)
    c, s = np.cos(th), np.sin(th)
    thd = -df / (A_HALF * s)
    thdd = -(ddf + A_HALF * c * thd**2) / (A_HALF * s)
    expected = (
        np.stack([f, A_HALF * s, th], axis=1),
        np.stack([df, A_HALF * c * thd, thd], axis=1),
        np.stack([ddf, A_HALF * (c * thdd - s * thd**2), thdd], axis=1),
    )
    for level, values in zip(("q", "qd", "qdd"), expected, strict=True):
        np.testing.assert_allclose(getattr(result, level), values, rtol=0, atol=1e-12, err_msg=level)


def test_a_crank_driven_out_of_its_reach_fails_its_assembly() -> None:
    """The crank's centre driven to x = 0.3, where the pin allows |x| <= a = 0.1: C_q is regular at the
    guess (its determinant -a sin(theta), theta = 0.5), so the mobility is verified, and damped Newton
    cannot assemble."""
    scenario = _x_driven(Constant(0.3))
    run = path.run(scenario, np.asarray(scenario.times()))
    assert (run.event, run.index, run.analysis) == (EVENTS[ASSEMBLY_FAILED], 0, None)


def test_a_slider_driven_beyond_its_stroke_stops_at_the_first_point_past_the_stroke_end() -> None:
    """stroke_fraction 1.2: no configuration after t* = asin(1 / 1.2) / 50; the kernel's halved steps
    towards the first grid point after t* fail there."""
    scenario = scenarios.build("slider_crank/slider_drive", overrides={"stroke_fraction": 1.2})
    grid = np.asarray(scenario.times())
    run = path.run(scenario, grid)
    first_after = int(np.argmax(grid > math.asin(1 / 1.2) / 50))
    assert (run.event, run.index) == (EVENTS[NOT_CONVERGED], first_after)


@pytest.mark.parametrize(("before", "after"), [(1e-3, 2e-4), (2e-4, 1e-3)], ids=["later", "earlier"])
def test_a_step_over_a_singularity_changes_the_sign_of_det_c_q(before: float, after: float) -> None:
    """Rod = crank = 0.2, driven from 0.5 rad at 50 rad/s: singular at theta = pi/2. A grid whose last
    step goes from t* - before to t* + after converges on the other side with det C_q of the other
    sign: the event is at that last index (11)."""
    scenario = scenarios.build("slider_crank", overrides={"rod_length": 0.2, "theta0": 0.5})
    t_star = (math.pi / 2 - 0.5) / 50
    grid = np.concatenate([np.linspace(0.0, t_star - before, 11), [t_star + after]])
    run = path.run(scenario, grid)
    assert (run.event, run.index) == (EVENTS[SIGN_CHANGE], 11)
    fine = path.run(scenario, grid[:11])  # without the last step the same grid completes
    assert fine.event == "ok" and fine.analysis is not None
    np.testing.assert_allclose(fine.analysis.q[:, 2], 0.5 + 50 * grid[:11], rtol=0, atol=1e-12)


def test_a_grid_point_on_a_singularity_is_near_singular() -> None:
    """Rod = crank from theta = 0 at 50 rad/s, 8 steps of pi/400 s: the point t = pi/100 (index 2) is
    theta = pi/2, where C_q is singular; the kernel stops there for the conditioning, or for Newton
    (whichever rounding decides, as in tests/reference_solver/compiled/test_path.py), at that index or
    before."""
    scenario = scenarios.build("slider_crank", overrides={"rod_length": 0.2, "theta0": 0.0, "steps": 8})
    grid = np.asarray(scenario.times())
    run = path.run(scenario, grid)
    assert run.event in (EVENTS[NEAR_SINGULAR], EVENTS[NOT_CONVERGED]) and run.index == 2
    assert grid[run.index] == pytest.approx(math.pi / 100, abs=1e-15)


def test_a_mechanism_near_a_singularity_keeps_its_conditioning_above_the_handover() -> None:
    """The same slider-crank on the grid up to index 1 (theta = pi/4): regular, the estimate of the
    reciprocal condition number within a factor 3 above the dense one, both above the handover."""
    scenario = scenarios.build("slider_crank", overrides={"rod_length": 0.2, "theta0": 0.0, "steps": 8})
    system = ConstraintSystem(scenario)
    grid = np.asarray(scenario.times())[:2]
    result = completed_run(scenario, grid)
    for k, t in enumerate(grid):
        exact = dense_scaled_rcond_1(system, result.q[k], t)
        assert exact * (1 - 1e-12) <= result.rcond[k] <= 3 * exact and exact > path.HANDOVER


def test_a_loose_tolerance_reports_the_residual_newton_stopped_at() -> None:
    """The four-bar at tolerance 1e-3: Newton stops after 2 iterations with residuals of 1e-11 to 1e-8
    (measured), each max |C| / L^power at the reported q (plain rows; rows in L = 0.05, the driver's
    an angle), to round-off."""
    scenario = scenarios.build("four_bar")
    residual_reported_in_row_units(scenario, 1e-9)
