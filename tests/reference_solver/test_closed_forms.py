"""The reference solver against closed forms of whole mechanisms over a full cycle."""

from __future__ import annotations

import numpy as np
import pytest

import scenarios
from reference_solver import solve
from scenarios.closed_form import exact

DISC_SCENARIOS = [name for name in scenarios.catalogue() if "spline" not in name]
LEVELS = ("position", "velocity", "acceleration")


def max_error(a, b, level):  # type: ignore[no-untyped-def]
    return float(np.max(np.abs(getattr(a, level) - getattr(b, level))))


@pytest.mark.parametrize("name", DISC_SCENARIOS)
def test_matches_closed_form(name: str) -> None:
    scenario = scenarios.build(name)
    solved, expected = solve(scenario), exact(scenario)
    assert solved.bodies == expected.bodies
    for level in LEVELS:
        assert max_error(solved, expected, level) < 1e-10, level
    if "contact.phi" in expected.extras:
        np.testing.assert_allclose(solved.extras["contact.phi"], expected.extras["contact.phi"], atol=1e-10)


@pytest.mark.parametrize(
    "overrides",
    [
        {"offset": -0.08, "theta0": 2.0},
        {"crank_length": 0.1, "rod_length": 0.35, "omega": -20.0, "revolutions": 2.0},
        {"drive": "slider", "offset": -0.05, "stroke_fraction": 0.6, "theta0": 1.0},
    ],
)
def test_slider_crank_other_parameters(overrides) -> None:  # type: ignore[no-untyped-def]
    scenario = scenarios.build("slider_crank", overrides=overrides)
    solved, expected = solve(scenario), exact(scenario)
    for level in LEVELS:
        assert max_error(solved, expected, level) < 1e-10 * max(
            1.0, float(np.abs(getattr(expected, level)).max())
        )


def test_planet_turns_at_arm_speed_times_one_plus_ratio() -> None:
    scenario = scenarios.build("planetary_gears", overrides={"radius_sun": 0.08, "radius_planet": 0.02})
    velocity = solve(scenario).velocity
    assert velocity is not None
    omega_arm, omega_planet = velocity[:, 0, 2], velocity[:, 1, 2]
    np.testing.assert_allclose(omega_planet, omega_arm * (1 + 0.08 / 0.02), rtol=1e-12)


def test_gear_ratios() -> None:
    for mesh, sign in (("external", -1.0), ("internal", 1.0)):
        scenario = scenarios.build(
            "spur_gears", overrides={"mesh": mesh, "radius_in": 0.04, "radius_out": 0.1}
        )
        velocity = solve(scenario).velocity
        assert velocity is not None
        np.testing.assert_allclose(velocity[:, 1, 2], sign * 0.4 * velocity[:, 0, 2], rtol=1e-12)


def test_rack_travels_radius_times_pinion_turn() -> None:
    scenario = scenarios.build("rack_pinion", overrides={"theta0": 0.7})
    position = solve(scenario).position
    assert position is not None
    np.testing.assert_allclose(position[:, 1, 0], 0.05 * (position[:, 0, 2] - 0.7), atol=1e-14)


@pytest.mark.parametrize("family", ["cam_knife_edge", "cam_roller", "cam_flat_face"])
def test_spline_cam_converges_to_the_disc(family: str) -> None:
    """A periodic cubic spline interpolates with O(h^4) error: refining the table converges."""
    exact_follower = exact(scenarios.build(family)).position[:, 1, 1]  # type: ignore[index]
    errors = []
    for knots in (12, 24, 48, 96):
        spline = scenarios.build(f"{family}/spline", overrides={"knots": knots})
        errors.append(float(np.max(np.abs(solve(spline).position[:, 1, 1] - exact_follower))))  # type: ignore[index]
    ratios = [errors[k] / errors[k + 1] for k in range(3)]
    assert all(r > 8 for r in ratios), (errors, ratios)
    assert errors[-1] < 1e-7
