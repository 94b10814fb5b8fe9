"""The plain kinematic loop (reference_solver.analysis, compiled=False) on a mechanism worked by hand.

A crank of length 2 a pinned at its end to the ground origin, its angle driven by the harmonic law
theta = m + A cos(w t): its frame origin (the centre) is at a (cos theta, sin theta), so
    x' = -a sin(theta) theta',  x'' = -a (cos(theta) theta'^2 + sin(theta) theta''),
    y' =  a cos(theta) theta',  y'' =  a (cos(theta) theta'' - sin(theta) theta'^2),
with theta' = -A w sin(w t), theta'' = -A w^2 cos(w t).
"""

from __future__ import annotations

import dataclasses
import math
import re
from typing import Any

import numpy as np
import pytest

import reference_solver.analysis as analysis
import scenarios
from reference_solver import AssemblyError, ConvergenceError, SingularConfigurationError, analyse, solve
from reference_solver.factorization import factorize
from reference_solver.limits import JUMP_FLOOR, JUMP_FRACTION
from reference_solver.newton import NewtonResult
from reference_solver.system import ConstraintSystem
from scenarios import (
    GROUND,
    AbsoluteDriver,
    Body,
    Constant,
    Harmonic,
    Point,
    Prismatic,
)
from scenarios.closed_form import exact
from scenarios.scenario import Scenario
from tests.support.hand_crank import (
    A_HALF,
    AMPLITUDE,
    MEAN,
    OMEGA,
    crank_by_hand,
    crank_scenario,
    unassembled_pair,
)


def test_positions_rates_and_accelerations_are_the_hand_worked_ones() -> None:
    scenario = crank_scenario()
    result = analyse(scenario, compiled=False)
    grid = np.asarray(scenario.times())
    np.testing.assert_array_equal(result.times, grid)
    for level, expected in zip(("q", "qd", "qdd"), crank_by_hand(grid), strict=True):
        np.testing.assert_allclose(getattr(result, level), expected, rtol=0, atol=1e-12, err_msg=level)
    assert np.all(result.residual < 1e-12)
    assert result.iterations[0] == 0 and np.all(result.iterations[1:] >= 1)
    assert np.all(result.rcond > 0.01)


def test_the_rates_solve_the_scaled_velocity_and_acceleration_equations() -> None:
    """_rates on the crank at the hand-worked q of t = 0.3 (theta' and theta'' both nonzero): the
    hand-worked q' and q''. The rows (pin, in L = 0.2; driver, an angle) and columns (x, y in L;
    theta) are scaled differently, so each scale used the wrong way round shows."""
    system = ConstraintSystem(crank_scenario())
    q, qd, qdd = (level[0] for level in crank_by_hand(np.array([0.3])))
    factors = factorize(system.scaled_jacobian(system.jacobian(q, 0.3)))
    rates = analysis._rates(system, factors, q, 0.3)
    np.testing.assert_allclose(rates[0], qd, rtol=0, atol=1e-12)
    np.testing.assert_allclose(rates[1], qdd, rtol=0, atol=1e-12)


def test_the_rates_of_a_driven_length() -> None:
    """A block sliding along the ground's x axis, its x driven by f = 0.4 + 0.7 cos(3 t) (L = 0.2):
    at t = 0.3, x' = f' = -2.1 sin(0.9) and x'' = f'' = -6.3 cos(0.9), y and theta still. Only a
    driver's C_t is nonzero, and this one is a length row (in units of L), unlike the crank's angle."""
    block = Scenario(
        family="hand_block",
        variant="default",
        bodies=(Body("block", (0.0, 0.0, 0.0)),),
        joints=(Prismatic("slide", Point("block"), Point(GROUND), axis=(1.0, 0.0)),),
        drivers=(AbsoluteDriver("push", "block", "x", Harmonic(MEAN, AMPLITUDE, OMEGA)),),
        t_end=1.0,
        steps=1,
        characteristic_length=2 * A_HALF,
    )
    system = ConstraintSystem(block)
    q = np.array([MEAN + AMPLITUDE * math.cos(0.9), 0.0, 0.0])
    factors = factorize(system.scaled_jacobian(system.jacobian(q, 0.3)))
    qd, qdd = analysis._rates(system, factors, q, 0.3)
    np.testing.assert_allclose(qd, [-2.1 * math.sin(0.9), 0, 0], rtol=0, atol=1e-12)
    np.testing.assert_allclose(qdd, [-6.3 * math.cos(0.9), 0, 0], rtol=0, atol=1e-12)


def test_the_predictor_is_the_second_order_taylor_step() -> None:
    """q + h q' + h^2/2 q'' with h = 0.5: 1 + 0.5 + 0.125 * 2, 2 + 0.5 + 0.125 * 4, 3 + 0.5 + 0.125 * 6."""
    predicted = analysis._predict(np.array([1.0, 2.0, 3.0]), np.ones(3), np.array([2.0, 4.0, 6.0]), 0.5)
    np.testing.assert_array_equal(predicted, [1.75, 3.0, 4.25])


def test_a_step_has_jumped_when_its_correction_exceeds_half_the_predictors_reach() -> None:
    """The crank's columns are scaled by L = 0.2 (x, y) and 1 (theta). A step h = 0.1 at theta' = 1
    reaches 0.1 in theta; at theta'' = 10 (theta' = 0) it reaches h^2 |theta''| = 0.1 too. Half of
    that, 0.05, is the largest correction on the branch: 0.04 in theta stays, 0.06 jumps, and so
    does 0.011 in x (0.055 in units of L), while 0.009 in x (0.045) stays."""
    system = ConstraintSystem(crank_scenario())
    assert JUMP_FRACTION == 0.5
    start = np.array([0.1, 0.0, 0.0])
    for qd, qdd in (([0.0, 0.0, 1.0], [0.0, 0.0, 0.0]), ([0.0, 0.0, 0.0], [0.0, 0.0, 10.0])):
        for offset, jumps in (((0, 0, 0.04), False), ((0, 0, 0.06), True), ((0.011, 0, 0), True),
                              ((0, -0.009, 0), False), ((0, 0, -0.06), True)):  # fmt: skip
            end = start + np.array(offset)
            assert analysis.jumped(system, np.array(qd), np.array(qdd), 0.1, start, end) is jumps, (
                qd,
                offset,
            )


def test_the_reach_of_a_length_coordinate_is_measured_in_units_of_l() -> None:
    """x' = 1 m/s over h = 0.1 reaches 0.1 m, 0.5 in units of L = 0.2: half of it, 0.25, is the
    largest correction on the branch. 0.2 rad in theta stays; 0.3 jumps."""
    system = ConstraintSystem(crank_scenario())
    start, qd, still = np.array([0.1, 0.0, 0.0]), np.array([1.0, 0.0, 0.0]), np.zeros(3)
    assert not analysis.jumped(system, qd, still, 0.1, start, start + np.array([0, 0, 0.2]))
    assert analysis.jumped(system, qd, still, 0.1, start, start + np.array([0, 0, 0.3]))


def test_a_step_that_reaches_nothing_has_jumped_beyond_the_floor() -> None:
    """With zero rates the reach is 0 and the floor JUMP_FLOOR = 1e-6 (scaled units) decides."""
    system = ConstraintSystem(crank_scenario())
    still, start = np.zeros(3), np.array([0.1, 0.0, 0.0])
    assert not analysis.jumped(system, still, still, 0.1, start, start + np.array([0, 0, 0.9 * JUMP_FLOOR]))
    assert analysis.jumped(system, still, still, 0.1, start, start + np.array([0, 0, 1.1 * JUMP_FLOOR]))


def _counting_approach(monkeypatch: pytest.MonkeyPatch) -> list[tuple[float, float]]:
    """Record each (t0, t1) the real analysis._approach is called on."""
    calls: list[tuple[float, float]] = []
    real = analysis._approach

    def counted(*args, **kwargs):  # type: ignore[no-untyped-def]
        calls.append((args[4], args[5]))
        return real(*args, **kwargs)

    monkeypatch.setattr(analysis, "_approach", counted)
    return calls


@pytest.mark.parametrize(
    "grid",
    [
        pytest.param(np.linspace(1.0, 0.0, 21), id="decreasing"),
        pytest.param(np.linspace(-1.0, 0.0, 21), id="negative times"),
    ],
)
def test_steps_newton_cannot_take_at_once_are_retaken_in_halves(
    grid: np.ndarray, monkeypatch: pytest.MonkeyPatch
) -> None:
    """With two Newton iterations allowed, some whole steps fail and are retaken in halved steps
    (analysis._approach), forwards and backwards in time alike: the answer is still the hand-worked one."""
    calls = _counting_approach(monkeypatch)
    result = analyse(crank_scenario(), grid, max_iterations=2, compiled=False)
    assert calls, "no step was retaken: the test does not reach analysis._approach"
    for level, expected in zip(("q", "qd", "qdd"), crank_by_hand(grid), strict=True):
        np.testing.assert_allclose(getattr(result, level), expected, rtol=0, atol=1e-12, err_msg=level)


def test_the_end_of_a_stroke_is_found_to_the_step_resolution() -> None:
    """A slider driven 1.2 times beyond its stroke leaves the crank no configuration after
    t* = asin(1 / 1.2) / omega (omega = 50). The halved steps stop when they are shorter than 1e-12
    times the time (about 2e-14 s here): the time the error names is within a few of those of t*
    (measured 1.7e-14 before t*; a resolution 1e-12 / t would leave 1e-10)."""
    scenario = scenarios.build("slider_crank/slider_drive", overrides={"stroke_fraction": 1.2})
    with pytest.raises(SingularConfigurationError) as caught:
        analyse(scenario, compiled=False)
    assert caught.value.time == pytest.approx(math.asin(1 / 1.2) / 50, abs=5e-14)


def test_a_dead_centre_loses_exactly_one_rank_and_the_message_names_the_rows() -> None:
    """At the slider-driven dead centre the crank and the rod line up: one mechanism, one lost
    direction, so C_q (square) loses exactly one rank. The message lists the dependent rows."""
    scenario = scenarios.build("slider_crank/slider_drive", overrides={"stroke_fraction": 1.0, "steps": 100})
    with pytest.raises(SingularConfigurationError) as caught:
        analyse(scenario, compiled=False)
    error = caught.value
    assert error.rank_deficiency == 1
    assert len(error.dependent_rows) >= 2 and "slider_drive.x" in error.dependent_rows
    assert str(error).endswith(f"C_q rank deficiency 1, dependent rows: {', '.join(error.dependent_rows)}")


def test_solve_runs_on_the_times_it_is_given() -> None:
    times = [0.0, 0.25, 0.5]
    trajectory = solve(crank_scenario(), times)
    np.testing.assert_array_equal(trajectory.times, times)
    assert trajectory.position is not None
    np.testing.assert_allclose(
        trajectory.position[:, 0], crank_by_hand(np.asarray(times))[0], rtol=0, atol=1e-12
    )


def test_solve_takes_the_fast_path_by_default(monkeypatch: pytest.MonkeyPatch) -> None:
    calls: list[str] = []
    real = analysis.compiled_path.analyse

    def counted(scenario, *args, **kwargs):  # type: ignore[no-untyped-def]
        calls.append(scenario.name)
        return real(scenario, *args, **kwargs)

    monkeypatch.setattr(analysis.compiled_path, "analyse", counted)
    solve(crank_scenario(), [0.0, 0.1])
    assert calls == ["hand_crank"]
    solve(crank_scenario(), [0.0, 0.1], compiled=False)
    assert calls == ["hand_crank"]


def test_half_steps_that_leave_the_branch_are_refused_too() -> None:
    """The undercut cam (see test_branch_guard.py) on a grid four times coarser than its own: whole
    steps jump, and so do some of their halves, which analysis._approach must refuse and halve again
    (measured: the same configurations as a grid 16 times finer, to 4e-16; accepting the jumping
    halves ends on another branch, 3.6 rad away)."""
    scenario = scenarios.build("cam_roller/stress_undercut")
    coarse = np.asarray(scenario.times(steps=scenario.steps // 4))
    fine = np.asarray(scenario.times(steps=4 * scenario.steps))
    reference = analyse(scenario, fine, compiled=False).q[::16]
    np.testing.assert_allclose(analyse(scenario, coarse, compiled=False).q, reference, rtol=0, atol=1e-12)


def _newton_failing_after(monkeypatch: pytest.MonkeyPatch, limit: float) -> None:
    """The real Newton-Raphson, made to fail (unconverged, no factors) at any time beyond `limit`."""
    real = analysis.newton

    def failing(system, q, t, settings):  # type: ignore[no-untyped-def]
        result = real(system, q, t, settings)
        return result if t <= limit else NewtonResult(result.q, False, settings.max_iterations, 1.0, None)

    monkeypatch.setattr(analysis, "newton", failing)


@pytest.mark.parametrize("limit", [0.5, 0.52])
def test_a_newton_failure_at_a_regular_configuration_is_a_convergence_error(
    limit: float, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Beyond `limit` no Newton converges; the crank there is regular (its pin and driver rows
    never become dependent), so the halved steps end in a ConvergenceError at the last time
    reached, with the hand-worked configuration of that time. From 0.5 (a grid time) no half step
    succeeds: the count is the allowed 25 iterations; towards 0.52 some do, and the count is the
    last successful Newton's (a few)."""
    _newton_failing_after(monkeypatch, limit)
    with pytest.raises(ConvergenceError) as caught:
        analyse(crank_scenario(), compiled=False)
    error = caught.value
    assert error.time == pytest.approx(limit, abs=1e-12)
    assert error.q is not None
    np.testing.assert_allclose(error.q, crank_by_hand(np.array([error.time]))[0][0], rtol=0, atol=1e-12)
    message = re.fullmatch(
        r"hand_crank: Newton-Raphson did not converge at t=0\.55 \(stuck at t=(\S+) after (\d+) "
        r"iterations\) at a regular configuration",
        str(error),
    )
    assert message is not None, str(error)
    assert float(message[1]) == pytest.approx(limit, abs=1e-6)
    assert (int(message[2]) == 25) is (limit == 0.5)


def test_solve_passes_its_tolerance_on() -> None:
    """Newton stops once its step and residual are below the tolerance (in units of L): with 0.1 the
    four-bar's first point keeps the error of its last step, measured 5.1e-9 m from the 1e-12 answer
    (on the crank above every tolerance gives the same numbers: its pin rows are linear once theta is
    right). Bounds: a third of that, and the tolerance itself times L."""
    scenario = scenarios.build("four_bar")
    loose = solve(scenario, [0.0, 0.001], tolerance=0.1).position
    tight = solve(scenario, [0.0, 0.001]).position
    assert loose is not None and tight is not None
    assert 1.7e-9 < np.max(np.abs(loose - tight)) < 0.1 * scenario.characteristic_length


def _renamed(item: Any, suffix: str) -> Any:
    """A copy of a scenario part whose bodies and constraints carry `suffix` (the ground keeps its name)."""
    if isinstance(item, tuple):
        return tuple(_renamed(v, suffix) for v in item)
    if not dataclasses.is_dataclass(item) or isinstance(item, type):
        return item
    changes = {}
    for f in dataclasses.fields(item):
        value = getattr(item, f.name)
        if f.name in ("body", "name") and isinstance(value, str) and value != GROUND:
            changes[f.name] = value + suffix
        elif isinstance(value, tuple) or dataclasses.is_dataclass(value):
            changes[f.name] = _renamed(value, suffix)
    return dataclasses.replace(item, **changes)


def test_two_mechanisms_at_their_stroke_ends_lose_two_ranks() -> None:
    """Two unconnected copies of the slider-crank driven 1.2 times beyond its stroke reach their
    stroke ends together: each loses one direction, so C_q loses two ranks and both sliders' driver
    rows are named. There the smallest singular value ratios are about 1.5e-7 (measured), lost for
    the singularity report's threshold NEAR_SINGULAR = 1e-4, not for the rank's default 1e-8."""
    one = scenarios.build("slider_crank/slider_drive", overrides={"stroke_fraction": 1.2})
    two = dataclasses.replace(
        one,
        bodies=one.bodies + _renamed(one.bodies, "_2"),
        joints=one.joints + _renamed(one.joints, "_2"),
        drivers=one.drivers + _renamed(one.drivers, "_2"),
        outputs=(),
    )
    with pytest.raises(SingularConfigurationError) as caught:
        analyse(two, compiled=False)
    assert caught.value.rank_deficiency == 2
    assert {"slider_drive.x", "slider_drive_2.x"} <= set(caught.value.dependent_rows)


def test_a_failed_assembly_names_the_four_worst_rows_beyond_ten_tolerances() -> None:
    """The scaled misses at the guess: da -0.09 / L^2 = -0.36, ya -0.1 / L = -0.2, db -0.04 / L^2 =
    -0.16, ta -1.08e-11, tb -1.03e-11, yb 0. The four worst are named, worst first, when they miss
    by more than 10 tolerances (1e-11: ta is, by 8 %); tb, fifth, is not. The two zero rows make
    C_q lose two ranks, and they are the dependent rows."""
    system, guess = unassembled_pair()
    with pytest.raises(AssemblyError) as caught:
        analysis.assemble(system, guess, 0.0, 1e-12)
    error = caught.value
    assert str(error) == (
        "unassembled: the mechanism cannot assemble at t=0: after 0 iterations the constraints "
        "da.length, ya.y, db.length, ta.theta still miss by up to 0.36 (relative to the "
        "characteristic length 0.5)"
    )
    assert error.time == 0.0
    assert error.q is not None
    np.testing.assert_array_equal(error.q, guess)
    assert error.rank_deficiency == 2
    assert error.dependent_rows == ("da.length", "db.length")


def test_a_driver_held_by_the_joints_only_at_the_configuration_is_named_with_the_dependent_rows() -> None:
    """The slider-crank driven at its slider's y instead of its crank: the slide's normal row holds y
    only while its angle row holds the slider level, so the three rows are independent at the
    generic points the mobility check draws and dependent at every assembled configuration. Newton
    meets the constraints there, C_q is singular, and the refusal says so rather than "miss by 1e-16"."""
    base = scenarios.build("slider_crank")
    held = AbsoluteDriver("slider_y", "slider", "y", Constant(0.0))
    with pytest.raises(AssemblyError) as caught:
        analyse(dataclasses.replace(base, drivers=(held,)))
    message = str(caught.value)
    assert message.startswith("slider_crank: the mechanism cannot assemble at t=0: the constraints hold (to ")
    assert (
        "but C_q is singular there, rank deficiency 1, dependent rows: slide.angle, slide.normal, " in message
    )
    assert "miss by" not in message
    assert caught.value.rank_deficiency == 1
    assert set(caught.value.dependent_rows) == {"slide.angle", "slide.normal", "slider_y.y"}


def _four_bar_turned(coordinate: int) -> tuple[ConstraintSystem, np.ndarray, np.ndarray]:
    """The four-bar, its closed-form configuration at t = 0 (bodies crank, coupler, rocker), and a
    guess with one angle (q[coordinate]) turned 2 rad back from it."""
    scenario = scenarios.build("four_bar")
    position = exact(scenario, np.array([0.0])).position
    assert position is not None
    truth = position[0].ravel()
    guess = truth.copy()
    guess[coordinate] -= 2.0
    return ConstraintSystem(scenario), truth, guess


@pytest.mark.parametrize("coordinate", [5, 8], ids=["coupler", "rocker"])
def test_assembly_from_a_rough_guess_is_damped_and_may_take_many_iterations(coordinate: int) -> None:
    """From the coupler's angle turned 2 rad back, plain Newton does not converge in 100 iterations
    (measured); from the rocker's, it lands 2 pi away; damped Newton reaches the closed form's
    configuration from both, from the rocker's in 26 iterations (measured: more than the 25 of a
    time step, fewer than the assembly's 100)."""
    system, truth, guess = _four_bar_turned(coordinate)
    np.testing.assert_allclose(analysis.assemble(system, guess, 0.0, 1e-12), truth, rtol=0, atol=1e-12)


def test_assembly_stops_at_its_tolerance() -> None:
    """With a tolerance of 0.1 (on both the step and the residual, scaled) the coupler-turned guess
    assembles 4.5e-5 L (measured) from the closed form: Newton stopped once both were below it,
    where a tolerance of 1e-12 on either goes on to round-off. Bounds: a third and three times."""
    system, truth, guess = _four_bar_turned(5)
    error = np.max(np.abs((analysis.assemble(system, guess, 0.0, 0.1) - truth) / system.column_scales))
    assert 1.5e-5 < error < 1.35e-4


def test_every_step_of_a_smooth_motion_is_taken_at_once(monkeypatch: pytest.MonkeyPatch) -> None:
    """On the crank's own grid the predictor q + h q' + h^2/2 q'' lies within h^3 |q'''| / 6 (about
    1e-4) of the answer: no step is retaken and each Newton ends in 3 iterations (measured), a
    predictor that left out a term, or a step believed longer than it is, would be retaken."""
    calls = _counting_approach(monkeypatch)
    result = analyse(crank_scenario(), compiled=False)
    assert calls == []
    assert np.all(result.iterations[1:] <= 3)


def test_a_grid_of_one_time_is_the_assembled_configuration_and_its_rates() -> None:
    result = analyse(crank_scenario(), [0.3], compiled=False)
    for level, expected in zip(("q", "qd", "qdd"), crank_by_hand(np.array([0.3])), strict=True):
        np.testing.assert_allclose(getattr(result, level), expected, rtol=0, atol=1e-12, err_msg=level)


def test_integer_times_give_a_float_grid_and_the_iterations_are_counts() -> None:
    for compiled in (True, False):
        result = analyse(crank_scenario(), [0, 1], compiled=compiled)
        assert result.times.dtype == np.float64
        assert result.iterations.dtype.kind == "i", compiled


def test_analyse_takes_the_fast_path_by_default(monkeypatch: pytest.MonkeyPatch) -> None:
    calls: list[float] = []
    real = analysis.compiled_path.analyse

    def counted(scenario, grid, tolerance, max_iterations):  # type: ignore[no-untyped-def]
        calls.append(tolerance)
        return real(scenario, grid, tolerance, max_iterations)

    monkeypatch.setattr(analysis.compiled_path, "analyse", counted)
    analyse(crank_scenario(), [0.0, 0.1])
    assert calls == [1e-12]


@pytest.mark.parametrize(("before", "after"), [(1e-3, 2e-4), (2e-4, 1e-3)], ids=["later", "earlier"])
def test_a_sign_change_of_det_c_q_is_reported_at_the_nearer_grid_point(before: float, after: float) -> None:
    """A slider-crank with rod = crank (0.2), driven from 0.5 rad at 50 rad/s, is singular at
    theta = pi/2, t* = (pi/2 - 0.5) / 50; a grid that steps over t* (its last two times t* - before
    and t* + after) sees det C_q change sign. The error names the time interpolated between them
    (measured 6.7e-8 s from t*, bounded by 2e-7) and the configuration of the grid point nearer the
    singularity, whose crank angle is the driven 0.5 + 50 t."""
    scenario = scenarios.build("slider_crank", overrides={"rod_length": 0.2, "theta0": 0.5})
    t_star = (math.pi / 2 - 0.5) / 50
    t0, t1 = t_star - before, t_star + after
    grid = np.concatenate([np.linspace(0.0, t0, 11), [t1]])
    with pytest.raises(SingularConfigurationError) as caught:
        analyse(scenario, grid, compiled=False)
    error = caught.value
    assert error.time == pytest.approx(t_star, abs=2e-7)
    assert error.q is not None
    assert error.q[2] == pytest.approx(0.5 + 50 * min((t0, t1), key=lambda t: abs(t - t_star)), abs=1e-12)
    assert (
        f"det C_q changed sign between t={t0:.6g} and t={t1:.6g} (a singular configuration or a jump to "
        "another assembly branch lies between)" in str(error)
    )


def test_a_grid_point_on_a_singularity_is_refused_for_its_conditioning() -> None:
    """The slider-crank with rod = crank from theta = 0 at 50 rad/s on 8 steps of pi/400 s: its grid
    point t = pi/100 is theta = pi/2, where C_q is singular, so its conditioning (below 1e-9) is the
    reason given, with its value."""
    scenario = scenarios.build("slider_crank", overrides={"rod_length": 0.2, "theta0": 0.0, "steps": 8})
    with pytest.raises(SingularConfigurationError) as caught:
        analyse(scenario, compiled=False)
    message = re.fullmatch(
        r"slider_crank: singular configuration at t=0\.0314159: "
        r"C_q reciprocal condition number (\S+); C_q rank deficiency 1, dependent rows: .+",
        str(caught.value),
    )
    assert message is not None, str(caught.value)
    assert float(message[1]) < 1e-9
