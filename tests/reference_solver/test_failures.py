"""What the reference solver refuses: singular configurations, impossible assemblies, bad mobility."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import scenarios
from reference_solver import (
    AssemblyError,
    MobilityError,
    SingularConfigurationError,
    analyse,
)
from scenarios import GROUND, AbsoluteDriver, Constant, Point, Revolute


def test_slider_driven_dead_centre_is_singular_at_the_right_time() -> None:
    """x = mean + half sin(omega t) with a full stroke reaches the outer dead centre (th2 = th3 = 0)
    at t = pi / (2 omega)."""
    scenario = scenarios.build("slider_crank/slider_drive", overrides={"stroke_fraction": 1.0, "steps": 100})
    with pytest.raises(SingularConfigurationError) as caught:
        analyse(scenario)
    error = caught.value
    assert error.time == pytest.approx(math.pi / 100, abs=1e-9)
    assert error.rank_deficiency >= 1
    assert "slider_drive.x" in error.dependent_rows
    assert error.q is not None
    assert abs(error.q[2]) < 1e-4 and abs(error.q[5]) < 1e-4  # crank and rod angles both ~0


def test_slider_driven_past_the_dead_centre_stops_where_the_stroke_ends() -> None:
    """With the stroke overshooting, no configuration exists beyond t* = asin(1 / f) / omega."""
    scenario = scenarios.build("slider_crank/slider_drive", overrides={"stroke_fraction": 1.2})
    with pytest.raises(SingularConfigurationError) as caught:
        analyse(scenario)
    assert caught.value.time == pytest.approx(math.asin(1 / 1.2) / 50, abs=1e-7)
    assert "no configuration beyond" in str(caught.value)


def test_crank_driven_equal_crank_and_rod_is_singular_at_right_angle() -> None:
    scenario = scenarios.build("slider_crank", overrides={"rod_length": 0.2, "theta0": 0.5})
    with pytest.raises(SingularConfigurationError) as caught:
        analyse(scenario)
    assert caught.value.time == pytest.approx((math.pi / 2 - 0.5) / 50, abs=1e-6)
    assert caught.value.rank_deficiency >= 1


def test_grid_point_on_the_singularity_is_caught_by_conditioning() -> None:
    """A grid point exactly at th2 = pi/2 has an exactly singular C_q."""
    scenario = scenarios.build("slider_crank", overrides={"rod_length": 0.2, "theta0": 0.0, "steps": 8})
    with pytest.raises(SingularConfigurationError) as caught:
        analyse(scenario)
    assert caught.value.time == pytest.approx(math.pi / 2 / 50, abs=1e-9)


def test_impossible_four_bar_fails_to_assemble_with_a_clear_message() -> None:
    scenario = scenarios.build("four_bar", overrides={"crank_length": 0.5})
    with pytest.raises(AssemblyError, match="cannot assemble at t=0"):
        analyse(scenario)


def test_over_driven_is_refused_with_counts() -> None:
    base = scenarios.build("four_bar")
    extra = AbsoluteDriver("rocker_hold", "rocker", "theta", Constant(1.0))
    scenario = dataclasses.replace(base, drivers=(*base.drivers, extra))
    with pytest.raises(
        MobilityError, match=r"over-driven: 2 driver equations .*crank_drive, rocker_hold.* for 1 degree"
    ):
        analyse(scenario)


def test_under_driven_is_refused_with_counts() -> None:
    base = scenarios.build("four_bar")
    scenario = dataclasses.replace(base, drivers=())
    with pytest.raises(MobilityError, match=r"under-driven: 0 driver equations \(none\) for 1 degree"):
        analyse(scenario)


def test_redundant_joint_is_refused_naming_the_rows() -> None:
    base = scenarios.build("four_bar")
    duplicate = Revolute("O4_again", Point(GROUND, (0.1, 0.0)), Point("rocker", (-0.0625, 0.0)))
    scenario = dataclasses.replace(base, joints=(*base.joints, duplicate))
    with pytest.raises(MobilityError, match="redundantly constrained") as caught:
        analyse(scenario)
    assert {"O4.x", "O4_again.x"} <= set(caught.value.dependent_rows)


def test_solution_never_contains_nan() -> None:
    for name in scenarios.catalogue():
        analysis = analyse(scenarios.build(name))
        for values in (analysis.q, analysis.qd, analysis.qdd):
            assert np.all(np.isfinite(values)), name
