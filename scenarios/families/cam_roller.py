"""Disc cam with a translating roller follower (see disc_cam for the geometry)."""

from __future__ import annotations

import math

from scenarios.bodies import Point
from scenarios.cams import RollerCam
from scenarios.families.disc_cam import PARAMETERS, disc_cam_family
from scenarios.family import length
from scenarios.scenario import ParameterValue


def _roller(p: dict[str, ParameterValue]) -> float:
    return float(p["roller_radius"])


FAMILY = disc_cam_family(
    "cam_roller",
    "driven disc cam, translating roller follower",
    lambda p, r, e, th: e * math.sin(th) + math.sqrt((r + _roller(p)) ** 2 - (e * math.cos(th)) ** 2),
    lambda p, profile, phi: RollerCam("contact", "cam", profile, Point("follower"), _roller(p), phi),
    parameters={**PARAMETERS, "roller_radius": length(0.02)},
    variants={
        # Stress variants: pressure angle up to asin(e / (R + r)) = 35 deg (e = 0.045 R does not
        # assemble from the family's guess); a spline through 6 knots; a roller of 0.95 times the
        # 0.032 m concave radius of curvature of a three-lobed cam's valleys (nearly undercut).
        "stress_steep": {"eccentricity": 0.04},
        "stress_few_knots": {"profile": "spline", "knots": 6},
        "stress_undercut": {"profile": "lobed", "roller_radius": 0.0304},
    },
)
