"""The engine-neutral vocabulary of planar mechanisms and the catalogue of mechanism families."""

from scenarios.bodies import GROUND, Body, Point
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
from scenarios.loading import load
from scenarios.motion_laws import Polynomial, TabulatedLaw
from scenarios.motions import Constant, ConstantSpeed, Harmonic
from scenarios.registry import all_families, build, catalogue, family
from scenarios.scenario import LEVELS, Scenario, ScenarioError
from scenarios.trajectory import Trajectory

__all__ = [
    "GROUND",
    "LEVELS",
    "AbsoluteDriver",
    "Body",
    "Constant",
    "ConstantSpeed",
    "EccentricDisc",
    "FlatFaceCam",
    "GearPair",
    "Ground",
    "Harmonic",
    "KnifeEdgeCam",
    "LobedProfile",
    "Point",
    "PointPathDriver",
    "Polynomial",
    "Prismatic",
    "RackPinion",
    "RelativeDisplacementDriver",
    "RelativeRotationDriver",
    "Revolute",
    "RevoluteRevolute",
    "RollerCam",
    "Scenario",
    "ScenarioError",
    "SplineProfile",
    "TabulatedLaw",
    "Trajectory",
    "all_families",
    "build",
    "catalogue",
    "family",
    "load",
]
