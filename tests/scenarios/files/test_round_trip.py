"""Every built-in scenario written as a scenario file and read back is the same scenario, and the
native solver gives bit-identical results from the file."""

from __future__ import annotations

import dataclasses
import math
import tomllib
import typing

import numpy as np
import pytest

import scenarios
from reference_solver import solve
from scenarios.cam_profiles import Profile
from scenarios.cams import CamContact
from scenarios.drivers import Driver
from scenarios.files import parse_scenario, scenario_toml, schema, writer
from scenarios.files.writer import read_back, toml_value
from scenarios.forces import Force
from scenarios.joints import Joint
from scenarios.motions import Motion

LEVELS = ("position", "velocity", "acceleration")


@pytest.mark.parametrize("name", scenarios.catalogue(include_stress=True, include_dynamic=True))
def test_every_scenario_reads_back_equal(name: str) -> None:
    scenario = scenarios.build(name)
    assert parse_scenario(scenario_toml(scenario), name) == read_back(scenario)


@pytest.mark.parametrize("name", scenarios.catalogue())
def test_every_family_solves_bit_identically_from_its_file(name: str) -> None:
    family = scenarios.build(name)
    from_file = parse_scenario(scenario_toml(family), f"{name}.toml")
    solved_family, solved_file = solve(family), solve(from_file)
    assert solved_file.bodies == solved_family.bodies
    for level in LEVELS:
        assert np.array_equal(solved_file.level(level), solved_family.level(level)), level
    assert solved_file.extras.keys() == solved_family.extras.keys()
    for key, values in solved_family.extras.items():
        assert np.array_equal(solved_file.extras[key], values), key


def test_overridden_family_round_trips() -> None:
    scenario = scenarios.build("four_bar", overrides={"branch": "-1", "omega": "-3.5"})
    assert parse_scenario(scenario_toml(scenario)) == read_back(scenario)


def test_numbers_are_written_exactly() -> None:
    """Shortest round-tripping reprs read back as the very same floats, specials included."""
    values = (0.1, 1 / 3, 2.0**-1074, 1e300, -0.0, math.pi * 1e-17, 12345678.901234567, math.inf, -math.inf)
    for value in values:
        back = tomllib.loads(f"v = {toml_value(value)}")["v"]
        assert back == value and math.copysign(1.0, back) == math.copysign(1.0, value)
    assert math.isnan(tomllib.loads(f"v = {toml_value(math.nan)}")["v"])
    quoted = 'a "quoted" name'
    assert tomllib.loads(f"v = {toml_value(quoted)}")["v"] == quoted


def test_new_motion_laws_round_trip_and_drive_the_native_solver() -> None:
    """A pendulum driven by each new law: the solved angle and its rates are the law's f, f', f''."""
    laws = (
        scenarios.Polynomial((0.2, 0.5, -0.25, 0.1)),
        scenarios.TabulatedLaw((0.0, 0.5, 1.0, 1.5, 2.0), (0.0, 0.4, 0.1, -0.3, 0.0), "periodic"),
        scenarios.TabulatedLaw((0.0, 0.7, 2.0), (0.1, 0.9, 0.4), "clamped", (0.0, -0.5)),
    )
    for law in laws:
        pendulum = scenarios.Scenario(
            family="pendulum",
            variant="default",
            bodies=(scenarios.Body("arm", (0.1, 0.0, 0.0)),),
            joints=(
                scenarios.Revolute(
                    "pivot", scenarios.Point(scenarios.GROUND), scenarios.Point("arm", (-0.1, 0.0))
                ),
            ),
            drivers=(scenarios.AbsoluteDriver("drive", "arm", "theta", law),),
            t_end=2.5,
            steps=50,
            characteristic_length=0.2,
        )
        assert parse_scenario(scenario_toml(pendulum)) == read_back(pendulum)
        solved = solve(pendulum)
        t = pendulum.times()
        for level, values in zip(LEVELS, (law.f, law.df, law.ddf), strict=True):
            got = solved.level(level)
            assert got is not None
            np.testing.assert_allclose(got[:, 0, 2], [values(x) for x in t], atol=1e-12)


def test_the_format_has_a_kind_for_every_class_of_the_vocabulary() -> None:
    """A class added to the vocabulary without a kind in the schema could not be written."""
    expected = {
        "joints": {
            *typing.get_args(Joint),
            *typing.get_args(CamContact),
            scenarios.GearPair,
            scenarios.RackPinion,
        },
        "drivers": set(typing.get_args(Driver)),
        "forces": set(typing.get_args(Force)),
        "motions": set(typing.get_args(Motion)),
        "profiles": set(typing.get_args(Profile)),
    }
    declared = {
        "joints": {k.cls for k in schema.JOINTS.values()},
        "drivers": {k.cls for k in schema.DRIVERS.values()},
        "forces": {k.cls for k in schema.FORCES.values()},
        "motions": {k.cls for k in schema.MOTIONS.values()},
        "profiles": {k.cls for k in schema.PROFILES.values()},
    }
    assert declared == expected


def test_a_field_the_format_cannot_hold_is_refused_not_dropped(monkeypatch: pytest.MonkeyPatch) -> None:
    # Format 1 holds every field of a Scenario now; a field added later without a key in the format
    # is refused rather than written without it (here: gravity, as if the format had no key for it).
    fields = {f.name for f in dataclasses.fields(scenarios.Scenario)}
    assert fields <= writer.WRITTEN | writer.NAME_TAGS | writer.ORIGIN
    point = dataclasses.replace(scenarios.build("four_bar"), point=(("omega", "5"),))
    with pytest.raises(scenarios.ScenarioError, match="cannot hold point"):
        scenario_toml(point)
    plain = scenarios.build("slider_crank")
    heavy = dataclasses.replace(plain, gravity=(0.0, -9.81))
    assert parse_scenario(scenario_toml(heavy)) == read_back(heavy)
    monkeypatch.setattr(writer, "WRITTEN", writer.WRITTEN - {"gravity"})
    assert parse_scenario(scenario_toml(plain)) == read_back(plain)
    with pytest.raises(scenarios.ScenarioError, match="cannot hold gravity"):
        scenario_toml(heavy)


def test_negative_zero_gravity_is_written() -> None:
    """A family built with gravity 0 has (0.0, -0.0): written as it is, it reads back bit for bit."""
    scenario = scenarios.build("compound_pendulum", overrides={"gravity": 0.0})
    assert "gravity = [0.0, -0.0]" in scenario_toml(scenario)
    back = parse_scenario(scenario_toml(scenario))
    assert [math.copysign(1.0, g) for g in back.gravity] == [1.0, -1.0]
