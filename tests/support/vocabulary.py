"""One scenario holding every constraint kind of the vocabulary (cams on all three profiles, an
internal gear on a carrier, non-unit axes and normals, offsets, every motion law)."""

from __future__ import annotations

from scenarios import GROUND, Point
from scenarios.bodies import Body
from scenarios.cam_profiles import EccentricDisc, LobedProfile, SplineProfile
from scenarios.cams import FlatFaceCam, KnifeEdgeCam, RollerCam
from scenarios.drivers import (
    AbsoluteDriver,
    PointPathDriver,
    RelativeDisplacementDriver,
    RelativeRotationDriver,
)
from scenarios.gears import GearPair, RackPinion
from scenarios.joints import Ground, Prismatic, Revolute, RevoluteRevolute
from scenarios.motions import Constant, ConstantSpeed, Harmonic
from scenarios.scenario import Scenario

NAMES = (
    "link",
    "slider",
    "gear1",
    "gear2",
    "carrier",
    "pinion",
    "rack",
    "cam1",
    "cam2",
    "cam3",
    "knife",
    "roller",
    "face",
)
DISC = EccentricDisc(0.05, 0.01)
VOCABULARY = Scenario(
    family="vocabulary",
    variant="default",
    bodies=tuple(Body(name, (0.0, 0.0, 0.0)) for name in NAMES),
    joints=(
        Ground("g", "carrier", (0.1, -0.2, 0.3)),
        Revolute("r0", Point(GROUND, (0.5, 0.2)), Point("link", (0.1, -0.3))),
        Revolute("r", Point("link", (0.3, 0.1)), Point("slider", (-0.2, 0.05))),
        Prismatic("p", Point("link", (0.1, 0.2)), Point("slider", (0.3, -0.1)), axis=(3.0, 4.0), angle=0.25),
        Prismatic("p0", Point(GROUND, (0.2, 0.1)), Point("rack", (0.3, -0.1)), axis=(0.0, 2.0), angle=-0.5),
        RevoluteRevolute("rr", Point("slider", (0.2, 0.1)), Point("gear1", (0.05, 0.0)), length=0.7),
        GearPair("gp", "gear1", 0.2, "gear2", 0.5, "carrier", True, 0.1, -0.2, 0.3),
        GearPair("gp0", "gear2", 0.3, "pinion", 0.1, theta0_i=0.4, theta0_j=0.7),
        RackPinion("rp", Point("pinion", (0.01, 0.02)), 0.1, Point("rack", (0.2, -0.1)), (1.0, 2.0), 0.03),
        KnifeEdgeCam("k", "cam1", DISC, Point("knife", (0.02, -0.01)), 0.3),
        RollerCam("rc", "cam2", SplineProfile.sample(DISC, 12), Point("roller", (0.01, 0.03)), 0.015, 1.0),
        FlatFaceCam("f", "cam3", LobedProfile(0.05, 0.01, 3), Point("face", (0.02, 0.01)), (0.0, -2.0), 2.0),
    ),
    drivers=(
        AbsoluteDriver("ax", "link", "x", ConstantSpeed(0.2, 1.5)),
        AbsoluteDriver("ay", "slider", "y", Harmonic(0.1, 0.3, 2.0, 0.5)),
        AbsoluteDriver("at", "cam1", "theta", Constant(0.7)),
        RelativeRotationDriver("rot", "gear2", "cam2", Harmonic(-0.2, 0.4, 3.0)),
        PointPathDriver(
            "path", Point("face", (0.1, 0.2)), ConstantSpeed(-0.3, 0.5), Harmonic(0.0, 0.2, 1.0, 1.0)
        ),
        RelativeDisplacementDriver(
            "disp",
            Point("knife", (0.1, 0.0)),
            Point("cam3", (0.0, 0.2)),
            Constant(0.05),
            ConstantSpeed(0.1, -2.0),
        ),
    ),
    t_end=1.0,
    steps=10,
    characteristic_length=0.5,
)
