"""The scenario file format, version 1, as data: every key each table accepts, its type and range.
(Gravity, analysis, forces, angle outputs and body rates were added to format 1 as optional keys.)

A table of a given `kind` maps one to one onto a vocabulary class: its keys are the class's field
names, required exactly when the field has no default. `docs/scenario-files.md` describes the same
format for people; the reader and the writer both work from these declarations alone.
"""

from __future__ import annotations

import difflib
import itertools
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

from scenarios.cam_profiles import EccentricDisc, LobedProfile, SplineProfile
from scenarios.cams import FlatFaceCam, KnifeEdgeCam, RollerCam
from scenarios.drivers import (
    AbsoluteDriver,
    PointPathDriver,
    RelativeDisplacementDriver,
    RelativeRotationDriver,
)
from scenarios.forces import AppliedForce, AppliedTorque, RotationalSpringDamper, SpringDamper
from scenarios.gears import GearPair, RackPinion
from scenarios.joints import Ground, Prismatic, Revolute, RevoluteRevolute
from scenarios.motion_laws import Polynomial, TabulatedLaw
from scenarios.motions import Constant, ConstantSpeed, Harmonic

FORMAT = 1
"""The version this reader reads and this writer writes (the file's top-level `format` key)."""


@dataclass(frozen=True)
class Key:
    """One key of a table: its type and, for numbers, its range.

    Types: number, integer, string, name (a string that is a name: scenarios.names), boolean,
    vec2, pose, numbers, strings, choice (one of
    `choices`), body (a body or the ground), moving_body (a body of the file), point, motion,
    profile, levels, parameters. Ranges: finite, positive, nonnegative, nonzero (a vector).
    """

    type: str
    range: str = "finite"
    choices: tuple[str, ...] = ()
    minimum_length: int = 0
    doc: str = ""
    """What the key means, for people (the JSON Schema's description)."""


NUMBER = Key("number")
POSITIVE = Key("number", "positive")
NONNEGATIVE = Key("number", "nonnegative")
NAME = Key("name")
BODY = Key("body")
MOVING_BODY = Key("moving_body")
POINT = Key("point")
MOTION = Key("motion")
PROFILE = Key("profile")
DIRECTION = Key("vec2", "nonzero")
KIND = Key("string")
"""The `kind` key of a table that it selects (joints, drivers, forces, motions, profiles)."""

TOP_LEVEL: dict[str, Key] = {
    "format": Key("integer", "positive"),
    "name": NAME,
    "variant": NAME,
    "description": Key("string"),
    "t_end": POSITIVE,
    "steps": Key("integer", "positive"),
    "characteristic_length": Key(
        "number",
        "positive",
        doc="m: position errors are divided by it (velocity errors by it times the rate)",
    ),
    "characteristic_rate": Key(
        "number",
        "positive",
        doc="rad/s: errors are divided by it to the power of their level (angles: rate^0, 1, 2; "
        "lengths: the length times that); default 2 pi / t_end",
    ),
    "outputs": Key("strings"),
    "levels": Key("levels"),
    "parameters": Key(
        "parameters",
        doc="older files only: where the file came from; not used to build, not written any more",
    ),
    "gravity": Key("vec2"),
    "analysis": Key("choice", choices=("kinematic", "dynamic")),
    "bodies": Key("tables", minimum_length=1),
    "joints": Key("tables"),
    "drivers": Key("tables"),
    "forces": Key("tables"),
    "angle_outputs": Key("tables"),
}
TOP_LEVEL_REQUIRED = ("format", "name", "t_end", "steps", "characteristic_length", "bodies")

BODY_KEYS: dict[str, Key] = {
    "name": NAME,
    "guess": Key("pose"),
    "mass": POSITIVE,
    "inertia": POSITIVE,
    "length": NONNEGATIVE,
    "rate": Key("pose"),
}

POINT_KEYS: dict[str, Key] = {"body": BODY, "local": Key("vec2")}

ANGLE_OUTPUT_KEYS: dict[str, Key] = {"name": NAME, "body": BODY, "relative_to": BODY}


@dataclass(frozen=True)
class Kind:
    """A table selected by its `kind` key: the class it builds, its keys, and a cross-key check
    returning (key, problem) for the first problem found, or None."""

    cls: type
    keys: dict[str, Key]
    check: Callable[[Mapping[str, Any]], tuple[str, str] | None] | None = None


def _distinct_points(v: Mapping[str, Any]) -> tuple[str, str] | None:
    if v["p_i"].body == v["p_j"].body:
        return "p_j.body", f"joins body '{v['p_i'].body}' to itself"
    return None


def _distinct_gears(v: Mapping[str, Any]) -> tuple[str, str] | None:
    if v["gear_i"] == v["gear_j"]:
        return "gear_j", f"meshes gear '{v['gear_i']}' with itself"
    return None


def _distinct_bodies(v: Mapping[str, Any]) -> tuple[str, str] | None:
    if v["body_i"] == v["body_j"]:
        return "body_j", f"joins body '{v['body_i']}' to itself"
    return None


def _reaction(v: Mapping[str, Any]) -> tuple[str, str] | None:
    if v.get("reaction") == v["body"]:
        return "reaction", f"is the body '{v['body']}' the torque acts on"
    return None


def _eccentric(v: Mapping[str, Any]) -> tuple[str, str] | None:
    if v["eccentricity"] >= v["radius"]:
        return "eccentricity", f"must be below the radius {v['radius']!r}, got {v['eccentricity']!r}"
    return None


def _lobed(v: Mapping[str, Any]) -> tuple[str, str] | None:
    if v["amplitude"] >= v["radius"]:
        return "amplitude", f"must be below the radius {v['radius']!r}, got {v['amplitude']!r}"
    return None


def _spline_profile(v: Mapping[str, Any]) -> tuple[str, str] | None:
    if any(r <= 0.0 for r in v["table"]):
        return "table", "radii must be positive"
    return None


def _tabulated(v: Mapping[str, Any]) -> tuple[str, str] | None:
    times, values = v["times"], v["values"]
    if len(values) != len(times):
        return "values", f"has {len(values)} entries for {len(times)} times"
    if any(b <= a for a, b in itertools.pairwise(times)):
        return "times", "must increase strictly"
    if v.get("ends", "clamped") == "periodic" and values[0] != values[-1]:
        return "values", f"a periodic law must end where it starts: {values[0]!r} != {values[-1]!r}"
    return None


JOINTS: dict[str, Kind] = {
    "ground": Kind(Ground, {"name": NAME, "body": MOVING_BODY, "pose": Key("pose")}),
    "revolute": Kind(Revolute, {"name": NAME, "p_i": POINT, "p_j": POINT}, _distinct_points),
    "prismatic": Kind(
        Prismatic,
        {"name": NAME, "p_i": POINT, "p_j": POINT, "axis": DIRECTION, "angle": NUMBER},
        _distinct_points,
    ),
    "revolute_revolute": Kind(
        RevoluteRevolute, {"name": NAME, "p_i": POINT, "p_j": POINT, "length": POSITIVE}, _distinct_points
    ),
    "gear_pair": Kind(
        GearPair,
        {
            "name": NAME,
            "gear_i": BODY,
            "radius_i": POSITIVE,
            "gear_j": BODY,
            "radius_j": POSITIVE,
            "carrier": BODY,
            "internal": Key("boolean"),
            "theta0_i": NUMBER,
            "theta0_j": NUMBER,
            "theta0_carrier": NUMBER,
        },
        _distinct_gears,
    ),
    "rack_pinion": Kind(
        RackPinion,
        {
            "name": NAME,
            "centre": POINT,
            "radius": POSITIVE,
            "rack": POINT,
            "axis": DIRECTION,
            "offset": NUMBER,
        },
    ),
    "knife_edge_cam": Kind(
        KnifeEdgeCam, {"name": NAME, "cam": BODY, "profile": PROFILE, "tip": POINT, "phi_guess": NUMBER}
    ),
    "roller_cam": Kind(
        RollerCam,
        {
            "name": NAME,
            "cam": BODY,
            "profile": PROFILE,
            "centre": POINT,
            "roller_radius": POSITIVE,
            "phi_guess": NUMBER,
        },
    ),
    "flat_face_cam": Kind(
        FlatFaceCam,
        {
            "name": NAME,
            "cam": BODY,
            "profile": PROFILE,
            "face": POINT,
            "normal": DIRECTION,
            "phi_guess": NUMBER,
        },
    ),
}

DRIVERS: dict[str, Kind] = {
    "absolute": Kind(
        AbsoluteDriver,
        {
            "name": NAME,
            "body": MOVING_BODY,
            "coordinate": Key("choice", choices=("x", "y", "theta")),
            "motion": MOTION,
        },
    ),
    "relative_rotation": Kind(
        RelativeRotationDriver, {"name": NAME, "body_i": BODY, "body_j": BODY, "motion": MOTION}
    ),
    "point_path": Kind(
        PointPathDriver, {"name": NAME, "point": POINT, "motion_x": MOTION, "motion_y": MOTION}
    ),
    "relative_displacement": Kind(
        RelativeDisplacementDriver,
        {"name": NAME, "p_i": POINT, "p_j": POINT, "motion_x": MOTION, "motion_y": MOTION},
        _distinct_points,
    ),
}

FORCES: dict[str, Kind] = {
    "applied_torque": Kind(
        AppliedTorque, {"name": NAME, "body": MOVING_BODY, "torque": MOTION, "reaction": BODY}, _reaction
    ),
    "applied_force": Kind(AppliedForce, {"name": NAME, "point": POINT, "fx": MOTION, "fy": MOTION}),
    "spring_damper": Kind(
        SpringDamper,
        {
            "name": NAME,
            "p_i": POINT,
            "p_j": POINT,
            "stiffness": NONNEGATIVE,
            "damping": NONNEGATIVE,
            "free_length": NONNEGATIVE,
        },
        _distinct_points,
    ),
    "rotational_spring_damper": Kind(
        RotationalSpringDamper,
        {
            "name": NAME,
            "body_i": BODY,
            "body_j": BODY,
            "stiffness": NONNEGATIVE,
            "damping": NONNEGATIVE,
            "free_angle": NUMBER,
        },
        _distinct_bodies,
    ),
}

MOTIONS: dict[str, Kind] = {
    "constant": Kind(Constant, {"value": NUMBER}),
    "constant_speed": Kind(ConstantSpeed, {"start": NUMBER, "rate": NUMBER}),
    "harmonic": Kind(Harmonic, {"mean": NUMBER, "amplitude": NUMBER, "omega": NUMBER, "phase": NUMBER}),
    "polynomial": Kind(Polynomial, {"coefficients": Key("numbers", minimum_length=1)}),
    "tabulated": Kind(
        TabulatedLaw,
        {
            "times": Key("numbers", minimum_length=3),
            "values": Key("numbers", minimum_length=3),
            "ends": Key("choice", choices=("clamped", "periodic")),
            "slopes": Key("vec2"),
        },
        _tabulated,
    ),
}

PROFILES: dict[str, Kind] = {
    "eccentric_disc": Kind(EccentricDisc, {"radius": POSITIVE, "eccentricity": NONNEGATIVE}, _eccentric),
    "lobed": Kind(
        LobedProfile,
        {"radius": POSITIVE, "amplitude": NONNEGATIVE, "lobes": Key("integer", "positive")},
        _lobed,
    ),
    "spline": Kind(SplineProfile, {"table": Key("numbers", minimum_length=3)}, _spline_profile),
}
SPLINE_CSV_KEY = "csv"
"""A spline profile may give `csv = "path"` (relative to the file) instead of an inline `table`."""

SECTIONS: dict[str, dict[str, Kind]] = {"joints": JOINTS, "drivers": DRIVERS, "forces": FORCES}


def in_range(value: float, range_: str) -> bool:
    """Whether a number lies in one of the declared ranges."""
    if not math.isfinite(value):
        return False
    return {"finite": True, "positive": value > 0.0, "nonnegative": value >= 0.0}[range_]


def kind_name(obj: object, kinds: Mapping[str, Kind]) -> str:
    """The `kind` under which a vocabulary object is written."""
    for name, kind in kinds.items():
        if type(obj) is kind.cls:
            return name
    raise TypeError(f"no scenario-file kind for {type(obj).__name__}")


def suggestion(word: str, choices: list[str]) -> str:
    """` (did you mean 'x'?)` for the closest choice, or nothing."""
    close = difflib.get_close_matches(word, choices, n=1)
    return f" (did you mean '{close[0]}'?)" if close else ""
