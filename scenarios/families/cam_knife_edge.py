"""Disc cam with a translating knife-edge follower (see disc_cam for the geometry)."""

from __future__ import annotations

import math

from scenarios.bodies import Point
from scenarios.cams import KnifeEdgeCam
from scenarios.families.disc_cam import disc_cam_family

FAMILY = disc_cam_family(
    "cam_knife_edge",
    "driven disc cam, translating knife-edge follower",
    lambda p, r, e, th: e * math.sin(th) + math.sqrt(r * r - (e * math.cos(th)) ** 2),
    lambda p, profile, phi: KnifeEdgeCam("contact", "cam", profile, Point("follower"), phi),
    variants={
        # Stress variants: pressure angle up to asin(e / R) = 64 deg; a spline through 6 knots.
        "stress_steep": {"eccentricity": 0.045},
        "stress_few_knots": {"profile": "spline", "knots": 6},
    },
)
