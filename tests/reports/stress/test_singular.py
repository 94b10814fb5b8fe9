"""The native solver reports each singular stress variant as singular, at the time closed-form
geometry gives; the stress suite declares those same times."""

from __future__ import annotations

import math

import pytest
from scipy.optimize import brentq

import scenarios
from reference_solver import SingularConfigurationError, analyse
from reports.stress.cases import CASES


def _parameters(name: str) -> dict[str, float]:
    scenario = scenarios.build(name)
    return {k: float(v) for k, v in scenario.parameters if not isinstance(v, str)}


def dead_centre_time() -> float:
    """x_B = mean + half sin(omega t) with half the full stroke reaches the outer dead centre
    (crank and rod in line, x_B = l2 + l3) at omega t = pi / 2."""
    return math.pi / 2 / _parameters("slider_crank/stress_dead_centre")["omega"]


def equal_links_time() -> float:
    """l2 = l3, no offset: sin th3 = -sin th2, and cos th3 = 0 first at th2 = pi / 2."""
    p = _parameters("slider_crank/stress_equal_links")
    assert p["crank_length"] == p["rod_length"] and p["offset"] == 0.0
    return (math.pi / 2 - p["theta0"]) / p["omega"]


def change_point_time() -> float:
    """g + a = b + c: the crank pointing back (th2 = pi) puts A on the ground line at g + a from
    O4, where coupler and rocker must stretch into that same line."""
    p = _parameters("four_bar/stress_change_point")
    g, a, b, c = (p[k] for k in ("ground_length", "crank_length", "coupler_length", "rocker_length"))
    assert g + a == pytest.approx(b + c, abs=1e-15)
    return (math.pi - p["theta0"]) / p["omega"]


def toggle_time() -> float:
    """The crank angle where |A - O4| reaches b + c (coupler and rocker in line), found by bisection."""
    p = _parameters("four_bar/stress_toggle")
    g, a, b, c = (p[k] for k in ("ground_length", "crank_length", "coupler_length", "rocker_length"))
    reach = lambda th: math.hypot(g - a * math.cos(th), a * math.sin(th)) - (b + c)  # noqa: E731
    angle = brentq(reach, p["theta0"], math.pi, xtol=1e-15)
    return (angle - p["theta0"]) / p["omega"]


SINGULAR = {
    # name: (closed-form time, how close the solver's time must be)
    "slider_crank/stress_dead_centre": (dead_centre_time, 1e-12),  # a grid point sits on it
    "slider_crank/stress_equal_links": (equal_links_time, 1e-8),  # det sign change, interpolated
    "four_bar/stress_change_point": (change_point_time, 1e-8),
    "four_bar/stress_toggle": (toggle_time, 1e-9),  # no configuration beyond: halved steps
}


@pytest.mark.parametrize("name", SINGULAR)
def test_native_solver_reports_singular_at_the_closed_form_time(name: str) -> None:
    expected, tolerance = SINGULAR[name]
    with pytest.raises(SingularConfigurationError) as caught:
        analyse(scenarios.build(name))
    assert caught.value.time == pytest.approx(expected(), abs=tolerance)
    assert caught.value.rank_deficiency >= 1


@pytest.mark.parametrize("name", SINGULAR)
def test_the_suite_declares_the_same_singular_time(name: str) -> None:
    declared = CASES[name].singular_time()
    assert declared is not None
    assert declared == pytest.approx(SINGULAR[name][0](), abs=1e-12)


def test_singular_variants_are_regular_before_their_time() -> None:
    """Up to just before the singular time the solution exists and is finite."""
    for name, (expected, _) in SINGULAR.items():
        scenario = scenarios.build(name)
        times = [t for t in scenario.times() if t < expected() - 1e-6]
        analysis = analyse(scenario, times)
        assert analysis.q.shape[0] == len(times), name


def test_near_change_point_is_not_singular_on_a_fine_grid_but_jumps_on_its_own() -> None:
    """1e-6 m short of the change point the branches pass close: on the scenario's grid the
    solver's predictor lands on the crossed branch and says so (a det sign change, 'or a jump');
    on a grid four times finer it follows the open branch to the end."""
    scenario = scenarios.build("four_bar/stress_near_change_point")
    with pytest.raises(SingularConfigurationError, match="jump to another assembly branch"):
        analyse(scenario)
    fine = scenario.times(steps=4 * scenario.steps)
    assert analyse(scenario, fine).q.shape[0] == len(fine)
