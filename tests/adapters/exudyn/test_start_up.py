"""Exudyn's start-up transient, its run-in and its outputs on its own steps: the four-bar's verdict
does not depend on how many outputs are asked for; without the run-in the transient is there and
shows as the start-up figure (reports.scoring.startup); even grids are read on Exudyn's steps (positions
at round-off), uneven ones interpolated with the cost said; the untuned setting at its measured
errors."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import adapters
from adapters.base import RunResult, Setting
from adapters.exudyn.run_in import DECAY, run_in_steps
from adapters.lattice import hermite, interpolation_cost, outputs_on_steps
from reports.scoring.comparison import measure
from reports.scoring.truth import independent_truth
from scenarios import Scenario, build
from tests.support.bounds import held

EXUDYN = adapters.load("exudyn")
LEVELS = ("error_velocity", "error_acceleration", "error_force")


def _measured(
    scenario: Scenario, setting: Setting | None = None, times: np.ndarray | None = None
) -> tuple[dict[str, float], RunResult]:
    grid = np.asarray(scenario.times() if times is None else times, dtype=float)
    run = EXUDYN.run(scenario, setting, grid)
    assert run.status == "ok", run.message
    metrics, _, _ = measure(scenario, run, independent_truth(scenario, grid).trajectory, None)
    return metrics, run


def _four_bar(outputs: int) -> Scenario:
    return dataclasses.replace(build("four_bar"), steps=outputs)


def test_the_four_bar_s_verdict_does_not_depend_on_the_number_of_outputs() -> None:
    """20, 200 and 2000 outputs over a turn: every level within a factor 2 (before the run-in the
    acceleration went 2.5e-4 / 5.7e-2 / 6.1e-2, the finer grids sampling the transient)."""
    found = [_measured(_four_bar(n))[0] for n in (20, 200, 2000)]
    for level in LEVELS:
        values = [m[level] for m in found]
        assert max(values) <= 2.0 * min(values), (level, values)
    assert all(m["error_position"] < 1e-14 for m in found)


def test_without_the_run_in_the_transient_shows_as_the_start_up_figure() -> None:
    """The exact start (run_in=0): the acceleration peaks near 5.7e-2 within the first steps, some
    800 times the settled error, for about 100 steps; after the run-in the first half is no worse
    than the second."""
    scenario = _four_bar(200)
    plain, _ = _measured(scenario, EXUDYN.default_setting(scenario).replace(run_in=0))
    held([plain["error_acceleration"], plain["startup_excess"]], [5.7e-2, 7.8e2], ("acceleration", "excess"))
    h = EXUDYN.default_setting(scenario)["dt"]
    assert 50 * h < plain["startup_time"] < 200 * h
    settled, _ = _measured(scenario)
    assert settled["startup_excess"] < 2.0 and settled["startup_time"] == 0.0


def test_the_run_in_lasts_until_the_double_root_s_envelope_is_gone() -> None:
    """n rho^n <= DECAY, the least such n: at rho 0.9, 250 steps."""
    for rho in (0.9, 0.6, 0.5):
        n = run_in_steps(rho)
        assert n * rho**n <= DECAY < (n - 1) * rho ** (n - 1)
    assert run_in_steps(0.9) == 250


def test_an_even_grid_is_read_on_exudyn_s_steps() -> None:
    """300 outputs over a turn of 2000 steps: the step shortens to a seventh of the output spacing
    and the positions are Exudyn's own, at round-off (interpolated between the rule's steps they
    were 2e-9 off)."""
    scenario = _four_bar(300)
    times = np.asarray(scenario.times())
    rule = EXUDYN.default_setting(scenario)["dt"]
    assert outputs_on_steps(times, rule) == pytest.approx((times[1] - times[0]) / 7, rel=1e-12)
    on_steps, run = _measured(scenario)
    assert on_steps["error_position"] < 1e-14 and not run.warnings
    uneven = times.copy()
    uneven[1] = 1.3 * times[1]
    between, run = _measured(scenario, times=uneven)
    held([between["error_position"]], [2.0e-9], ("interpolated position",))
    (warning,) = run.warnings
    cost = float(warning.split("about ")[1].split(" ")[0])
    assert between["error_position"] / 3 < cost < between["error_position"] * 3


def test_the_interpolation_cost_is_zero_on_a_quintic_and_not_on_a_sextic() -> None:
    h, s = 0.1, 0.37

    def ends(p: np.poly1d) -> tuple[tuple[np.ndarray, ...], tuple[np.ndarray, ...]]:
        d1, d2 = p.deriv(), p.deriv(2)
        return tuple((np.array([p(t)]), np.array([d1(t)]), np.array([d2(t)])) for t in (0.0, h))  # type: ignore[return-value]

    quintic = np.poly1d([3.0, -1.0, 2.0, 0.5, -2.0, 1.0])
    left, right = ends(quintic)
    cubic_error = abs(hermite(s, h, left, right)[0][0] - quintic(s * h))
    assert interpolation_cost(s, h, left, right)[0] == pytest.approx(cubic_error, rel=1e-9)
    sextic = np.poly1d([1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    left, right = ends(sextic)
    assert interpolation_cost(s, h, left, right)[0] > 0.0


UNTUNED: dict[str, tuple[float, float, float, float]] = {
    "four_bar": (3.0e-13, 8.7e-6, 5.7e-2, 2.5e-2),
    "slider_crank": (1.0e-13, 1.6e-6, 6.1e-3, 3.7e-3),
}
"""Exudyn's own defaults at the rule's step, 200 outputs: (P, V, A, force), measured;
positions at Exudyn's default Newton tolerance, accelerations and forces carrying the transient."""


@pytest.mark.parametrize("name", list(UNTUNED))
def test_the_untuned_setting_at_its_measured_errors(name: str) -> None:
    scenario = build(name)
    setting = EXUDYN.untuned_setting(scenario)
    assert setting is not None and setting.mode == "untuned"
    assert setting["dt"] == EXUDYN.default_setting(scenario)["dt"]
    found, _ = _measured(scenario, setting)
    held(
        [found["error_position"], *(found[level] for level in LEVELS)],
        UNTUNED[name],
        ("position", "velocity", "acceleration", "force"),
        round_off=1e-14,
    )


def test_a_motion_with_no_configuration_before_its_start_runs_without_a_run_in_and_says_so() -> None:
    """The slider driven 1.6 times past the crank's reach: its dead centre lies 0.675 / omega before
    the start, inside the run-in's 0.785 / omega; after it, 0.675 / omega ahead, past the grid."""
    scenario = build("slider_crank/slider_drive", overrides={"stroke_fraction": 1.6})
    times = np.linspace(0.0, 0.3 / float(scenario.parameter("omega")), 11)
    result = EXUDYN.run(scenario, times=times)
    assert result.status == "ok", result.message
    assert any("no run-in" in w and "did not converge" in w for w in result.warnings), result.warnings


def test_a_run_in_is_refused_where_it_has_no_meaning() -> None:
    assert math.isfinite(run_in_steps(0.0))
    free = build("four_bar_gravity")
    result = EXUDYN.run(free, EXUDYN.default_setting(free).replace(run_in=10))
    assert result.status == "failed" and "run_in" in result.message
