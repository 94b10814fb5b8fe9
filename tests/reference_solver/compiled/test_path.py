"""The compiled compiled path against the plain path it must reproduce: same answers to 1e-12 on every
scenario, and every failure diagnosed exactly as the plain path does it."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import scenarios
from reference_solver import AssemblyError, MobilityError, SingularConfigurationError, SolverError, analyse
from reference_solver.compiled import path
from scenarios import GROUND, AbsoluteDriver, Constant, Point, Revolute
from scenarios.scenario import Scenario

STEPS = 50  # the plain path costs about 1.4 ms a point


def both(scenario: Scenario, tolerance: float = 1e-12):  # type: ignore[no-untyped-def]
    grid = np.asarray(scenario.times(steps=STEPS))
    compiled = path.run(scenario, grid, tolerance)
    return compiled, analyse(scenario, grid, tolerance, compiled=False)


@pytest.mark.parametrize("name", scenarios.catalogue())
def test_fast_path_gives_the_plain_answer(name: str) -> None:
    compiled, plain = both(scenarios.build(name))
    assert compiled.event == "ok", compiled.event  # the kernel itself ran the whole grid
    result = compiled.analysis
    assert result is not None
    for level in ("q", "qd", "qdd"):
        expected = getattr(plain, level)
        scale = max(1.0, float(np.max(np.abs(expected))))
        np.testing.assert_allclose(
            getattr(result, level), expected, rtol=0, atol=1e-12 * scale, err_msg=level
        )
    np.testing.assert_array_equal(result.iterations, plain.iterations)
    assert result.iterations.dtype == plain.iterations.dtype == np.int64
    assert result.layout == plain.layout  # what trajectory() reads the columns with
    np.testing.assert_allclose(result.residual, plain.residual, rtol=0, atol=1e-14)
    # Both estimate the 1-norm reciprocal condition number (LAPACK's estimator, on differently
    # pivoted factors): measured within a factor 2.1 of each other on the catalogue.
    ratio = result.rcond / plain.rcond
    assert np.all((ratio > 1 / 3) & (ratio < 3))


def test_looser_tolerance_gives_the_plain_answer_too() -> None:
    compiled, plain = both(scenarios.build("four_bar"), tolerance=1e-6)
    assert compiled.analysis is not None
    np.testing.assert_array_equal(compiled.analysis.iterations, plain.iterations)
    np.testing.assert_allclose(compiled.analysis.q, plain.q, rtol=0, atol=1e-12)


def test_analyse_uses_the_fast_path_by_default() -> None:
    scenario = scenarios.build("slider_crank")
    grid = np.asarray(scenario.times())
    default, compiled = analyse(scenario), path.run(scenario, grid).analysis
    assert compiled is not None
    np.testing.assert_array_equal(default.qdd, compiled.qdd)  # the very same numbers


def test_without_numba_analyse_runs_the_plain_path(monkeypatch: pytest.MonkeyPatch) -> None:
    from reference_solver import compiled as compiled_package

    scenario = scenarios.build("four_bar", overrides={"steps": 20})
    monkeypatch.setattr(compiled_package, "AVAILABLE", False)
    plain_only = analyse(scenario)
    monkeypatch.undo()
    np.testing.assert_array_equal(plain_only.qdd, analyse(scenario, compiled=False).qdd)


def _failure(scenario: Scenario) -> tuple[type, str, float | None, int, tuple[str, ...]]:
    with pytest.raises(SolverError) as caught:
        analyse(scenario)
    e = caught.value
    return type(e), str(e), e.time, e.rank_deficiency, e.dependent_rows


def _plain_failure(scenario: Scenario) -> tuple[type, str, float | None, int, tuple[str, ...]]:
    with pytest.raises(SolverError) as caught:
        analyse(scenario, compiled=False)
    e = caught.value
    return type(e), str(e), e.time, e.rank_deficiency, e.dependent_rows


ON_THE_SINGULARITY = {"near-singular C_q", "Newton-Raphson failed"}  # whichever rounding decides
SINGULAR = {
    # scenario, the kernel's events and the grid time where it stops
    "dead centre reached": (
        scenarios.build("slider_crank/slider_drive", overrides={"stroke_fraction": 1.0, "steps": 100}),
        {"near-singular C_q"},
        math.pi / 100,
    ),
    "stroke beyond the dead centre": (
        scenarios.build("slider_crank/slider_drive", overrides={"stroke_fraction": 1.2}),
        {"Newton-Raphson failed"},
        None,
    ),
    "equal crank and rod, crossed between grid points": (
        scenarios.build("slider_crank", overrides={"rod_length": 0.2, "theta0": 0.5}),
        {"det C_q changed sign"},
        None,
    ),
    "equal crank and rod, on a grid point": (
        scenarios.build("slider_crank", overrides={"rod_length": 0.2, "theta0": 0.0, "steps": 8}),
        ON_THE_SINGULARITY,
        math.pi / 2 / 50,
    ),
    "chain turning back where the links line up": (
        scenarios.build("four_bar_chain", overrides={"amplitude": math.pi / 2}),
        ON_THE_SINGULARITY,
        math.pi / 2 / 10,
    ),
}


@pytest.mark.parametrize("case", SINGULAR)
def test_singular_configurations_are_caught_by_the_kernel_and_diagnosed_as_plain(case: str) -> None:
    scenario, events, when = SINGULAR[case]
    grid = np.asarray(scenario.times())
    run = path.run(scenario, grid)
    assert run.event in events and run.analysis is None
    if when is not None:
        assert grid[run.index] == pytest.approx(when, abs=1e-12)
    failure = _failure(scenario)
    assert failure[0] is SingularConfigurationError
    assert failure == _plain_failure(scenario)
    assert failure[2] is not None and failure[2] <= grid[run.index] + 1e-12  # not after the kernel stopped


def test_a_mechanism_that_cannot_assemble_is_diagnosed_as_plain() -> None:
    scenario = scenarios.build("four_bar", overrides={"crank_length": 0.5})
    assert path.run(scenario, np.asarray(scenario.times())).analysis is None
    failure = _failure(scenario)
    assert failure[0] is AssemblyError and failure == _plain_failure(scenario)


BASE = scenarios.build("four_bar")
SECOND_O4 = Revolute("O4_again", Point(GROUND, (0.1, 0.0)), Point("rocker", (-0.0625, 0.0)))
MOBILITY = {
    "over-driven": dataclasses.replace(
        BASE, drivers=(*BASE.drivers, AbsoluteDriver("rocker_hold", "rocker", "theta", Constant(1.0)))
    ),
    "under-driven": dataclasses.replace(BASE, drivers=()),
    "redundant": dataclasses.replace(
        BASE,
        joints=(
            *BASE.joints,
            Revolute("O4_again", Point(GROUND, (0.1, 0.0)), Point("rocker", (-0.0625, 0.0))),
        ),
    ),
}


@pytest.mark.parametrize("case", MOBILITY)
def test_mobility_errors_are_the_plain_ones(case: str) -> None:
    scenario = MOBILITY[case]
    run = path.run(scenario, np.asarray(scenario.times()))
    assert "not a square system" in run.event and run.index == 0 and run.analysis is None
    failure = _failure(scenario)
    assert failure[0] is MobilityError and failure == _plain_failure(scenario)


def test_lobed_profile_kernel_gives_the_plain_answer() -> None:
    scenario = scenarios.build("cam_roller", overrides={"profile": "lobed", "roller_radius": 0.01})
    compiled, plain = both(scenario)
    assert compiled.event == "ok" and compiled.analysis is not None
    for level in ("q", "qd", "qdd"):
        expected = getattr(plain, level)
        atol = 1e-12 * max(1.0, float(np.max(np.abs(expected))))
        np.testing.assert_allclose(getattr(compiled.analysis, level), expected, rtol=0, atol=atol)


def test_an_empty_grid_and_an_unhashable_scenario() -> None:
    """No time point: no kernel run; a scenario that cannot be a cache key (a list for a tuple) is
    compiled all the same and gives the same motion."""
    scenario = scenarios.build("four_bar", overrides={"steps": 10})
    assert path.run(scenario, np.zeros(0)) == path.FastRun("empty grid", 0, None)
    unhashable = dataclasses.replace(scenario, parameters=[("note", 1.0)])  # type: ignore[arg-type]
    grid = np.asarray(scenario.times())
    kept, fresh = path.run(scenario, grid).analysis, path.run(unhashable, grid).analysis
    assert kept is not None and fresh is not None
    np.testing.assert_array_equal(fresh.qdd, kept.qdd)
    np.testing.assert_array_equal(fresh.times, grid)


def test_the_iteration_limit_reaches_the_kernel() -> None:
    """Newton allowed no iteration never converges, even at the first grid point (converged needs a
    step below the tolerance, and none was taken); allowed one, it converges in one at every point."""
    scenario = scenarios.build("four_bar", overrides={"steps": 10})
    grid = np.asarray(scenario.times())
    assert path.run(scenario, grid, 1e-12, 0) == path.FastRun("Newton-Raphson failed", 0, None)
    one = path.run(scenario, grid, 1e-12, 1).analysis
    assert one is not None
    np.testing.assert_array_equal(one.iterations, [0] + [1] * 10)
    again = path.analyse(scenario, grid, 1e-12, 1)
    assert again is not None
    np.testing.assert_array_equal(again.iterations, one.iterations)
