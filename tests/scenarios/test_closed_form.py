"""The closed forms where the mutation run (docs/mutation.md) found them unchecked: gears started
at another angle, the cams' contact parameter, the refusals and their reasons, and a grid of the
caller's. The expected values are the native solver's (reference_solver), an independent
construction from the constraint equations."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import scenarios
from reference_solver import solve
from scenarios.closed_form import NoClosedForm, exact

LEVELS = ("position", "velocity", "acceleration")


@pytest.mark.parametrize("name", ["spur_gears", "spur_gears/internal", "planetary_gears", "rack_pinion"])
def test_gears_started_at_another_angle_match_the_native_solver(name: str) -> None:
    scenario = scenarios.build(name, overrides={"theta0": 0.7, "steps": 24})
    solved, expected = solve(scenario), exact(scenario)
    for level in LEVELS:
        np.testing.assert_allclose(
            getattr(solved, level), getattr(expected, level), atol=1e-10, err_msg=level
        )


@pytest.mark.parametrize("name", ["cam_knife_edge", "cam_roller", "cam_flat_face"])
def test_a_disc_cam_s_closed_form_carries_the_contact_parameter(name: str) -> None:
    scenario = scenarios.build(name, overrides={"steps": 24})
    expected = exact(scenario)
    assert set(expected.extras) == {"contact.phi"}
    np.testing.assert_allclose(
        expected.extras["contact.phi"], solve(scenario).extras["contact.phi"], atol=1e-10
    )


def test_what_has_no_closed_form_is_refused_with_its_reason() -> None:
    spline = scenarios.build("cam_roller/spline")
    with pytest.raises(NoClosedForm, match="eccentric disc profile only"):
        exact(spline)
    base = scenarios.build("slider_crank")
    with pytest.raises(NoClosedForm, match="not a family with one"):
        exact(dataclasses.replace(base, family="trammel"))
    edited = dataclasses.replace(base, drivers=())  # the family's joints, its driver removed
    with pytest.raises(NoClosedForm, match="not the mechanism the family slider_crank builds"):
        exact(edited)


def test_the_caller_s_grid_is_the_trajectory_s() -> None:
    scenario = scenarios.build("four_bar")
    times = [0.0, 0.01, 0.02]
    trajectory = exact(scenario, times)
    assert trajectory.times.dtype == float and list(trajectory.times) == times
    assert trajectory.position is not None and trajectory.position.shape[0] == 3
    assert exact(scenario, [0, 1]).times.dtype == float  # whole seconds given as integers


def test_every_kinematic_family_declares_its_closed_form_and_no_dynamic_one_does() -> None:
    """A kinematic family without one would be measured against the native solver only, silently."""
    families = scenarios.all_families().values()
    assert {f.name for f in families if f.closed_form is not None} == {
        f.name for f in families if not f.dynamic
    }
    dynamic = scenarios.build("compound_pendulum")
    with pytest.raises(NoClosedForm, match="not a family with one"):
        exact(dynamic)
