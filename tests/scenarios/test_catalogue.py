"""The scenario catalogue: names, parameters, variants and what each scene declares."""

from __future__ import annotations

import math
import re

import pytest

import scenarios
from scenarios import ScenarioError
from scenarios.trajectory import Trajectory

FAMILIES = [
    "slider_crank",
    "four_bar",
    "spur_gears",
    "planetary_gears",
    "rack_pinion",
    "cam_knife_edge",
    "cam_roller",
    "cam_flat_face",
    "four_bar_chain",
]


DYNAMIC_FAMILIES = [
    "compound_pendulum",
    "four_bar_gravity",
    "slider_crank_spring",
    "andrews_squeezer",
    "n_four_bar",
    "stiff_spring",
]


def test_the_catalogue_has_the_families_of_the_architecture() -> None:
    known = scenarios.all_families()
    assert [n for n, f in known.items() if not f.dynamic] == FAMILIES
    assert [n for n, f in known.items() if f.dynamic] == DYNAMIC_FAMILIES
    assert all(scenarios.build(n).analysis == "dynamic" for n in DYNAMIC_FAMILIES)
    assert not set(DYNAMIC_FAMILIES) & set(scenarios.catalogue())


def test_slider_crank_and_four_bar_bodies_and_parameters() -> None:
    sc = scenarios.build("slider_crank")
    assert sc.body_names == ("crank", "rod", "slider")
    assert {"crank_length", "rod_length", "offset", "omega", "theta0", "drive"} <= set(
        scenarios.family("slider_crank").defaults
    )
    fb = scenarios.build("four_bar")
    assert fb.body_names == ("crank", "coupler", "rocker")
    assert {"ground_length", "crank_length", "coupler_length", "rocker_length", "omega", "theta0"} <= set(
        scenarios.family("four_bar").defaults
    )


def test_default_four_bar_is_a_grashof_crank_rocker() -> None:
    p = scenarios.family("four_bar").defaults
    lengths = sorted(
        float(p[k]) for k in ("ground_length", "crank_length", "coupler_length", "rocker_length")
    )  # type: ignore[arg-type]
    assert lengths[0] + lengths[3] < lengths[1] + lengths[2]
    assert float(p["crank_length"]) == lengths[0]  # type: ignore[arg-type]


def test_parameters_are_typed_from_strings() -> None:
    sc = scenarios.build("four_bar", overrides={"crank_length": "0.04", "steps": "50"})
    assert sc.parameter("crank_length") == 0.04 and sc.steps == 50
    with pytest.raises(ScenarioError, match="steps must be an integer"):
        scenarios.build("four_bar", overrides={"steps": "2.5"})


@pytest.mark.parametrize(
    ("name", "overrides", "message"),
    [
        ("slider_crank", {"drive": "piston"}, "drive must be one of crank, slider, got 'piston'"),
        ("slider_crank", {"omega": 0}, "omega must be a number in [-1e+06, 1e+06] rad/s, not 0"),
        ("cam_roller", {"eccentricity": 0.06}, "eccentricity must be in [0, radius)"),
        ("cam_flat_face", {"profile": "ellipse"}, "profile must be one of disc, spline, lobed"),
        (
            "spur_gears",
            {"mesh": "internal", "radius_out": 0.01},
            "internal mesh needs radius_out > radius_in",
        ),
        ("four_bar", {"coupler_length": float("nan")}, "coupler_length must be a number in (0, 1e+06] m"),
    ],
)
def test_non_physical_values_are_refused(name: str, overrides: dict, message: str) -> None:
    with pytest.raises(ScenarioError, match=re.escape(message)):
        scenarios.build(name, overrides=overrides)


def test_each_scene_declares_only_what_it_needs() -> None:
    gears = scenarios.build("spur_gears")
    assert len(gears.bodies) == 2 and not gears.cams
    cam = scenarios.build("cam_roller")
    assert len(cam.cams) == 1 and cam.body_names == ("cam", "follower")


def test_trajectory_frame_round_trip() -> None:
    import numpy as np

    times = np.linspace(0, 1, 5)
    traj = Trajectory(
        times, ("a",), position=np.random.default_rng(0).normal(size=(5, 1, 3)), extras={"k.phi": times * 2}
    )
    back = Trajectory.from_frame(traj.to_frame())
    assert back.bodies == ("a",) and back.velocity is None
    np.testing.assert_array_equal(back.position, traj.position)  # type: ignore[arg-type]
    np.testing.assert_array_equal(back.extras["k.phi"], times * 2)


def test_spline_profile_evaluates_scipys_periodic_spline() -> None:
    """The profile's own piecewise evaluation is scipy's periodic cubic spline, on any turn."""
    import math

    import numpy as np
    from scipy.interpolate import CubicSpline

    table = (0.5, 0.55, 0.48, 0.6, 0.52, 0.45, 0.5, 0.58)
    knots = np.linspace(0, 2 * math.pi, len(table) + 1)
    reference = CubicSpline(knots, [*table, table[0]], bc_type="periodic")
    profile = scenarios.SplineProfile(table)
    for phi in np.linspace(-7.0, 13.0, 301):
        wrapped = float(np.mod(phi, 2 * math.pi))
        expected = [float(reference(wrapped, order)) for order in range(4)]
        got = profile.radii(float(phi))
        np.testing.assert_allclose(got[:3], expected[:3], rtol=1e-12, atol=1e-12)
        if min(abs(wrapped - k) for k in knots) > 1e-9:  # the third derivative jumps at knots
            np.testing.assert_allclose(got[3], expected[3], rtol=1e-12, atol=1e-12)


def test_every_declared_parameter_refuses_what_lies_outside_its_range() -> None:
    """Each parameter of each family: its default lies in range, and NaN, inf, a value past either
    limit and a word where a number belongs are refused with the range in the message."""
    for family in scenarios.all_families().values():
        for key, parameter in family.parameters.items():
            assert parameter.check(family.name, key, parameter.default) == parameter.default
            if parameter.choices:
                bad: list[object] = ["no such choice"]
            else:
                bad = [float("nan"), float("inf"), "a word"]
                if math.isfinite(parameter.high):
                    bad.append(parameter.high * 10 if parameter.high > 0 else 1.0)
                if math.isfinite(parameter.low):
                    bad.append(parameter.low if parameter.low_open else parameter.low - 1)
            for value in bad:
                with pytest.raises(ScenarioError, match=re.escape(parameter.describe())):
                    scenarios.build(family.name, overrides={key: value})  # type: ignore[dict-item]
