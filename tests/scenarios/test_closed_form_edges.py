"""Closed forms where the mutation run (docs/mutation.md) found them unchecked: the refusals' whole
reasons, the disc cams' contact parameter for a cam started past half a turn (its branch is then
chosen from a start angle and a contact angle far from 0), and a four-bar started at theta = 0
exactly. The expected values are the native solver's (reference_solver), an independent
construction from the constraint equations."""

from __future__ import annotations

import dataclasses
import re
import warnings

import numpy as np
import pytest

import scenarios
from reference_solver import solve
from scenarios.closed_form import NoClosedForm, exact


def test_the_refusals_give_their_whole_reason() -> None:
    with pytest.raises(NoClosedForm, match=r"^closed forms exist for the eccentric disc profile only$"):
        exact(scenarios.build("cam_roller/spline"))
    base = scenarios.build("slider_crank")
    reason = (
        f"{base.name}: no closed form: not the mechanism the family slider_crank builds "
        "from the parameters it records"
    )
    with pytest.raises(NoClosedForm, match=f"^{re.escape(reason)}$"):
        exact(dataclasses.replace(base, drivers=()))


@pytest.mark.parametrize("theta0", [4.0, -3.5, 9.0])
@pytest.mark.parametrize("name", ["cam_knife_edge", "cam_roller", "cam_flat_face"])
def test_a_disc_cam_started_past_half_a_turn_keeps_the_native_contact_branch(
    name: str, theta0: float
) -> None:
    scenario = scenarios.build(name, overrides={"theta0": theta0, "steps": 24})
    np.testing.assert_allclose(
        exact(scenario).extras["contact.phi"], solve(scenario).extras["contact.phi"], atol=1e-10
    )


def test_a_four_bar_started_at_zero_matches_the_native_solver() -> None:
    """At theta = 0 exactly sin(theta) is exactly 0: a closed form dividing by it is NaN there."""
    scenario = scenarios.build("four_bar", overrides={"theta0": 0.0, "steps": 24})
    solved, expected = solve(scenario), exact(scenario)
    for level in ("position", "velocity", "acceleration"):
        np.testing.assert_allclose(getattr(solved, level), getattr(expected, level), atol=1e-9, err_msg=level)


def test_a_four_bar_past_its_dead_points_is_nan_there_without_a_warning() -> None:
    """A non-Grashof four-bar (0.09 + 0.125 > 0.1 + 0.1) turned a whole revolution: the closed form
    is finite until the triangle of coupler, rocker and diagonal A-O4 first fails to close
    (|b - c| <= d <= b + c), NaN from there on (the branch is lost), and raises no floating-point
    warning."""
    g, a, b, c = 0.1, 0.09, 0.1, 0.125
    scenario = scenarios.build("four_bar", overrides={"crank_length": a, "theta0": 0.0})
    t = np.asarray(scenario.times(steps=720))
    with np.errstate(all="raise"), warnings.catch_warnings():
        warnings.simplefilter("error")
        frame = exact(scenario, t).to_frame()
    th2 = float(scenario.parameter("omega")) * t
    d = np.hypot(g - a * np.cos(th2), a * np.sin(th2))
    closes = (abs(b - c) <= d) & (d <= b + c)
    assert 0 < closes.sum() < t.size
    lost = np.logical_or.accumulate(~closes)
    np.testing.assert_array_equal(np.isnan(frame["coupler.theta"].to_numpy()), lost)
