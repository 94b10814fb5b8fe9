"""Kinds no built-in family uses (ground joints, massless links, point-path and relative drivers,
internal gears on a carrier, lobed and flat-faced cams) written out and read back; a mechanism
driven by each driver kind solved natively from its file."""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np

from reference_solver import solve
from scenarios.bodies import GROUND, Body, Point
from scenarios.cam_profiles import LobedProfile, SplineProfile
from scenarios.cams import FlatFaceCam, KnifeEdgeCam, RollerCam
from scenarios.drivers import (
    AbsoluteDriver,
    PointPathDriver,
    RelativeDisplacementDriver,
    RelativeRotationDriver,
)
from scenarios.files import parse_scenario, scenario_toml
from scenarios.files.writer import read_back
from scenarios.gears import GearPair, RackPinion
from scenarios.joints import Ground, Prismatic, Revolute, RevoluteRevolute
from scenarios.motion_laws import Polynomial, TabulatedLaw
from scenarios.motions import Constant, Harmonic
from scenarios.scenario import Scenario

BODIES = tuple(
    Body(n, (0.1 * k, -0.2 * k, 0.3 * k), 0.5 + k, 1e-3 * (k + 1), 0.1 * k) for k, n in enumerate("abcd")
)


def _scenario(name: str, joints: tuple[Any, ...], drivers: tuple[Any, ...]) -> Scenario:
    return Scenario(name, "default", BODIES, joints, drivers, t_end=1.2, steps=24, characteristic_length=0.1)


def test_every_joint_and_optional_key_round_trips() -> None:
    joints = (
        Ground("fix", "a", (0.1, 0.2, 0.3)),
        RevoluteRevolute("rod", Point("a", (0.1, 0.0)), Point("b", (-0.1, 0.05)), 0.25),
        Prismatic("slide", Point("b"), Point("c", (0.3, 0.0)), axis=(0.6, 0.8), angle=0.2),
        GearPair(
            "ring",
            "c",
            0.05,
            "d",
            0.15,
            carrier="a",
            internal=True,
            theta0_i=0.1,
            theta0_j=-0.2,
            theta0_carrier=0.3,
        ),
        GearPair("fixed_sun", GROUND, 0.1, "b", 0.02, carrier="c"),
        RackPinion(
            "rack", Point("d", (0.0, 0.01)), 0.03, Point("a", (0.0, -0.03)), axis=(0.0, 1.0), offset=0.01
        ),
        KnifeEdgeCam("knife", "a", LobedProfile(0.05, 0.01, 3), Point("b"), 0.4),
        RollerCam("roller", "c", SplineProfile((0.05, 0.06, 0.055, 0.045)), Point("d"), 0.01, 1.2),
        FlatFaceCam("flat", "b", LobedProfile(0.04, 0.002, 2), Point("c", (0.0, 0.01)), (0.0, -1.0), 2.0),
    )
    drivers = (
        AbsoluteDriver("x_of_a", "a", "x", Polynomial((0.1, 0.2, 0.3, 0.4))),
        RelativeRotationDriver("turn", "b", GROUND, Harmonic(0.1, 0.2, 3.0, 0.5)),
        PointPathDriver(
            "path",
            Point("c", (0.1, 0.0)),
            Constant(0.2),
            TabulatedLaw((0.0, 1.0, 2.0), (0.0, 1.0, 0.0), "periodic"),
        ),
        RelativeDisplacementDriver(
            "apart",
            Point("a"),
            Point("d"),
            Constant(0.1),
            TabulatedLaw((0.0, 0.5, 1.0), (0.0, 0.2, 0.1), "clamped", (0.3, -0.1)),
        ),
    )
    scenario = dataclasses.replace(
        _scenario("every_kind", joints, drivers),
        variant="v2",
        outputs=("b", "d"),
        levels=("position", "velocity"),
    )
    parameters = (("note", "synthetic"), ("count", 3), ("scale", 0.5))
    scenario = dataclasses.replace(scenario, parameters=parameters, description='kinds "no family" uses')
    assert parse_scenario(scenario_toml(scenario)) == read_back(scenario)


def test_every_driver_kind_solves_from_its_file() -> None:
    """a is fixed by a ground joint; b turns about it by a relative rotation; c's point follows a
    path with c's angle held; d keeps a prescribed offset from c and turns with it."""
    x_law = TabulatedLaw((0.0, 0.4, 1.0), (0.2, 0.3, 0.25), "clamped", (0.0, 0.0))
    joints = (Ground("fix", "a", (0.0, 0.0, 0.0)), Revolute("hinge", Point("a"), Point("b", (-0.1, 0.0))))
    drivers = (
        RelativeRotationDriver("turn", "b", "a", Polynomial((0.1, 0.5, -0.2))),
        PointPathDriver("path", Point("c", (0.05, 0.0)), x_law, Harmonic(0.1, 0.05, 4.0)),
        AbsoluteDriver("hold", "c", "theta", Constant(0.0)),
        RelativeDisplacementDriver("offset", Point("d"), Point("c"), Constant(0.2), Polynomial((0.0, 0.1))),
        RelativeRotationDriver("with_c", "d", "c", Constant(0.0)),
    )
    scenario = _scenario("drivers", joints, drivers)
    from_file = parse_scenario(scenario_toml(scenario))
    solved, direct = solve(from_file), solve(scenario)
    for level in ("position", "velocity", "acceleration"):
        assert np.array_equal(solved.level(level), direct.level(level))
    t = np.asarray(scenario.times())
    position = solved.position
    assert position is not None
    np.testing.assert_allclose(position[:, 2, 0], [x_law.f(s) - 0.05 for s in t], atol=1e-12)
    np.testing.assert_allclose(position[:, 3, 0] - position[:, 2, 0], 0.2, atol=1e-12)
    np.testing.assert_allclose(position[:, 3, 1] - position[:, 2, 1], 0.1 * t, atol=1e-12)
    np.testing.assert_allclose(position[:, 1, 2], 0.1 + 0.5 * t - 0.2 * t**2, atol=1e-12)
