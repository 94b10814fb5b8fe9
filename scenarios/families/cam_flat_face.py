"""Disc cam with a translating flat-faced follower (see disc_cam for the geometry)."""

from __future__ import annotations

import math

from scenarios.bodies import Point
from scenarios.cams import FlatFaceCam
from scenarios.families.disc_cam import disc_cam_family

FAMILY = disc_cam_family(
    "cam_flat_face",
    "driven disc cam, translating flat-faced follower",
    lambda p, r, e, th: r + e * math.sin(th),
    lambda p, profile, phi: FlatFaceCam("contact", "cam", profile, Point("follower"), (0.0, -1.0), phi),
)
