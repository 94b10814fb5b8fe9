"""Each row's power of length, seen where it matters: the scaled residual C / L^power of a displaced
constraint does not change when the whole mechanism, and its characteristic length L, is measured in
other units. A length row scales as s, an area row (the distance link's) as s^2, an angle row not at
all; a wrong power leaves a factor of s (here 10) in the scaled row."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pytest

from scenarios import (
    AbsoluteDriver,
    ConstantSpeed,
    EccentricDisc,
    FlatFaceCam,
    GearPair,
    Ground,
    KnifeEdgeCam,
    Point,
    PointPathDriver,
    Prismatic,
    RackPinion,
    RelativeDisplacementDriver,
    RelativeRotationDriver,
    Revolute,
    RevoluteRevolute,
    RollerCam,
)
from scenarios.scenario import Constraint
from tests.support.constraint_systems import Pose, coordinates, system_of

Case = Callable[[float], tuple[Constraint, dict[str, Pose]]]


def _moved(s: float) -> dict[str, Pose]:
    """a and b displaced (lengths times s), both turned: every row below is off by a nonzero amount."""
    return {"a": (0.3 * s, -0.2 * s, 0.4), "b": (-0.1 * s, 0.5 * s, -0.3)}


def _speed(value: float, rate: float) -> ConstantSpeed:
    return ConstantSpeed(value, rate)


CASES: dict[str, Case] = {
    "ground": lambda s: (Ground("g", "a", (0.1 * s, 0.2 * s, 0.1)), _moved(s)),
    "revolute": lambda s: (Revolute("r", Point("a", (0.2 * s, 0.0)), Point("b", (0.0, 0.1 * s))), _moved(s)),
    "prismatic": lambda s: (
        Prismatic("p", Point("a", (0.1 * s, 0.0)), Point("b"), axis=(3.0, 4.0), angle=0.2),
        _moved(s),
    ),
    "revolute_revolute": lambda s: (
        RevoluteRevolute("rr", Point("a", (0.2 * s, 0.1 * s)), Point("b"), 0.1 * s),
        _moved(s),
    ),
    "gear_pair": lambda s: (GearPair("m", "a", 0.2 * s, "b", 0.1 * s, carrier="c"), _moved(s)),
    "rack_pinion": lambda s: (
        RackPinion("rp", Point("a"), 0.2 * s, Point("b", (0.1 * s, 0.0)), axis=(3.0, 4.0), offset=0.05 * s),
        _moved(s),
    ),
    "absolute_driver_x": lambda s: (AbsoluteDriver("d", "a", "x", _speed(0.1 * s, 0.2 * s)), _moved(s)),
    "absolute_driver_y": lambda s: (AbsoluteDriver("d", "a", "y", _speed(0.1 * s, 0.2 * s)), _moved(s)),
    "absolute_driver_theta": lambda s: (AbsoluteDriver("d", "a", "theta", _speed(0.1, 0.2)), _moved(s)),
    "relative_rotation": lambda s: (RelativeRotationDriver("d", "a", "b", _speed(0.1, 0.2)), _moved(s)),
    "point_path": lambda s: (
        PointPathDriver("d", Point("a", (0.1 * s, 0.0)), _speed(0.1 * s, 0.2 * s), _speed(-0.1 * s, 0.3 * s)),
        _moved(s),
    ),
    "relative_displacement": lambda s: (
        RelativeDisplacementDriver(
            "d", Point("a", (0.1 * s, 0.0)), Point("b"), _speed(0.1 * s, 0.2 * s), _speed(-0.1 * s, 0.3 * s)
        ),
        _moved(s),
    ),
    "knife_edge_cam": lambda s: (
        KnifeEdgeCam("k", "a", EccentricDisc(0.3 * s, 0.1 * s), Point("b", (0.1 * s, 0.0)), 0.0),
        _moved(s),
    ),
    "roller_cam": lambda s: (
        RollerCam("k", "a", EccentricDisc(0.3 * s, 0.1 * s), Point("b", (0.1 * s, 0.0)), 0.2 * s, 0.0),
        _moved(s),
    ),
    "flat_face_cam": lambda s: (
        FlatFaceCam("k", "a", EccentricDisc(0.3 * s, 0.1 * s), Point("b", (0.1 * s, 0.0)), (3.0, 4.0), 0.0),
        _moved(s),
    ),
}
PHI = 0.7  # a cam contact's profile parameter, an angle


def _scaled_residual(case: Case, s: float) -> np.ndarray:
    constraint, poses = case(s)
    system = system_of(constraint, length=s)
    phis = (PHI,) * len(system.layout.contacts)
    return system.residual(coordinates(poses, phis), 0.5) / system.row_scales


@pytest.mark.parametrize("kind", CASES)
def test_the_scaled_residual_does_not_depend_on_the_unit_of_length(kind: str) -> None:
    metres, decimetres = _scaled_residual(CASES[kind], 1.0), _scaled_residual(CASES[kind], 10.0)
    assert np.all(np.abs(metres) > 1e-3)  # every row is displaced, so a stray factor of 10 shows
    np.testing.assert_allclose(decimetres, metres, rtol=1e-12, atol=0)
