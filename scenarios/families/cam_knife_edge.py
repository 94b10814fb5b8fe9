"""Disc cam with a translating knife-edge follower (see disc_cam for the geometry)."""

from __future__ import annotations

import math

from scenarios.bodies import Point
from scenarios.cams import KnifeEdgeCam
from scenarios.families.disc_cam import PARAMETERS, SPLINE_VARIANTS, build_disc_cam, disc_cam_closed_form
from scenarios.family import Family
from scenarios.scenario import ParameterValue, Scenario


def _build(p: dict[str, ParameterValue], variant: str) -> Scenario:
    return build_disc_cam(
        "cam_knife_edge",
        p,
        variant,
        lambda r, e, th: e * math.sin(th) + math.sqrt(r * r - (e * math.cos(th)) ** 2),
        lambda profile, phi: KnifeEdgeCam("contact", "cam", profile, Point("follower"), phi),
    )


FAMILY = Family(
    name="cam_knife_edge",
    summary="driven disc cam, translating knife-edge follower",
    parameters=PARAMETERS,
    build=_build,
    closed_form=disc_cam_closed_form,
    variants={
        **SPLINE_VARIANTS,
        # Stress variants: pressure angle up to asin(e / R) = 64 deg; a spline through 6 knots.
        "stress_steep": {"eccentricity": 0.045},
        "stress_few_knots": {"profile": "spline", "knots": 6},
    },
)
