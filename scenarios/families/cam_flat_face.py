"""Disc cam with a translating flat-faced follower (see disc_cam for the geometry)."""

from __future__ import annotations

import math

from scenarios.bodies import Point
from scenarios.cams import FlatFaceCam
from scenarios.families.disc_cam import PARAMETERS, SPLINE_VARIANTS, build_disc_cam, disc_cam_closed_form
from scenarios.family import Family
from scenarios.scenario import ParameterValue, Scenario


def _build(p: dict[str, ParameterValue], variant: str) -> Scenario:
    return build_disc_cam(
        "cam_flat_face",
        p,
        variant,
        lambda r, e, th: r + e * math.sin(th),
        lambda profile, phi: FlatFaceCam("contact", "cam", profile, Point("follower"), (0.0, -1.0), phi),
    )


FAMILY = Family(
    name="cam_flat_face",
    summary="driven disc cam, translating flat-faced follower",
    parameters=PARAMETERS,
    build=_build,
    closed_form=disc_cam_closed_form,
    variants=SPLINE_VARIANTS,
)
