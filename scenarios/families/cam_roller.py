"""Disc cam with a translating roller follower (see disc_cam for the geometry)."""

from __future__ import annotations

import math

from scenarios.bodies import Point
from scenarios.cams import RollerCam
from scenarios.families.disc_cam import PARAMETERS, SPLINE_VARIANTS, build_disc_cam, disc_cam_closed_form
from scenarios.family import Family, length
from scenarios.scenario import ParameterValue, Scenario


def _build(p: dict[str, ParameterValue], variant: str) -> Scenario:
    rr = float(p["roller_radius"])
    return build_disc_cam(
        "cam_roller",
        p,
        variant,
        lambda r, e, th: e * math.sin(th) + math.sqrt((r + rr) ** 2 - (e * math.cos(th)) ** 2),
        lambda profile, phi: RollerCam("contact", "cam", profile, Point("follower"), rr, phi),
    )


FAMILY = Family(
    name="cam_roller",
    summary="driven disc cam, translating roller follower",
    parameters={**PARAMETERS, "roller_radius": length(0.02)},
    build=_build,
    closed_form=disc_cam_closed_form,
    variants={
        **SPLINE_VARIANTS,
        # Stress variants: pressure angle up to asin(e / (R + r)) = 35 deg (e = 0.045 R does not
        # assemble from the family's guess); a spline through 6 knots; a roller of 0.95 times the
        # 0.032 m concave radius of curvature of a three-lobed cam's valleys (nearly undercut).
        "stress_steep": {"eccentricity": 0.04},
        "stress_few_knots": {"profile": "spline", "knots": 6},
        "stress_undercut": {"profile": "lobed", "roller_radius": 0.0304},
    },
)
