"""MuJoCo's knife edge on a faceted cam: a sphere centred on the tip rolling on the facets of the
profile's inward offset by its radius r. Its geometry (the offset of a circle is the concentric
circle, the sphere's centre is r from the offset everywhere on the profile, a cam thinner than the
sphere refused) and its errors against the native solver, falling with the piece count and as r nears
the smallest radius of curvature rho.

Measured with MuJoCo 4.0 at the rule's default (RK4, dt = 1/2000 of the cam's turn, tc 4 steps,
contact solimp 0.99, preload 100 N), follower errors against the native solver on
cam_knife_edge/spline (m, m/s, m/s^2; wall time of one run, build included, on a shared machine):

    r / rho   pieces  offset sagitta  position  velocity  acceleration  time
    0.8          64    1.7e-5         2.0e-5    6.8e-3    13            1.5 s
    0.8         128    4.3e-6         6.0e-6    3.1e-3    6.5           1.4 s
    0.8         256    1.1e-6         3.7e-6    8.3e-4    2.1           1.2 s
    0.8         512    2.7e-7         2.6e-6    1.9e-4    1.1           2.5 s
    0.8        1024    6.8e-8         1.8e-6    1.2e-4    0.71          5.7 s
    0.8        2048    1.7e-8         1.3e-6    9.5e-5    0.32          7.4 s
    0.02        512    1.3e-6         4.9e-5    8.7e-2    510           2.6 s
    0.05        512    1.3e-6         3.7e-5    7.4e-2    509           2.0 s
    0.1         512    1.2e-6         2.6e-5    2.5e-2    66            2.0 s
    0.2         512    1.1e-6         3.9e-6    2.7e-3    16            2.3 s
    0.4         512    8.1e-7         3.0e-6    1.4e-3    7.4           4.0 s
    0.6         512    5.4e-7         2.9e-6    7.6e-4    2.8           2.6 s
    0.9         512    1.4e-7         2.4e-6    1.1e-4    0.65          2.6 s
    0.95        512    6.8e-8         2.2e-6    6.3e-5    0.36          2.5 s
    cam_knife_edge/stress_few_knots (6 knots), 0.8, 512:  2.7e-6, 1.8e-4, 1.2

A small sphere is the bare knife edge again (thrown off every vertex: 510 m/s^2, the preload over
the mass); from r = 0.2 rho it runs below the spline roller's errors at the same 512 pieces (3.9e-6,
2.4e-3, 15: test_cam_facets), and the errors fall as r nears rho (on a circle the offset shrinks to
a point at r = rho) and with the piece count, at order 0.5 (position, velocity) and 0.85
(acceleration) from 512 to 2048. Unlike the bare facets, 64 pieces no longer throw it off.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import scenarios
from adapters.mujoco import MujocoAdapter, cam_tip
from adapters.mujoco.cam_facets import DEFAULT_PIECES, sagitta, vertices
from adapters.mujoco.cam_tip import curvature_radii, tip_radius, tip_reason
from scenarios.bodies import Point
from scenarios.cam_profiles import EccentricDisc, SplineProfile
from scenarios.cams import KnifeEdgeCam
from tests.support.bounds import held
from tests.support.mujoco.cam_follower import follower_errors
from tests.support.mujoco.offset_curve import offset_point

ADAPTER = MujocoAdapter()
DISC = SplineProfile.sample(EccentricDisc(0.05, 0.01), 72)
"""The spline of cam_knife_edge/spline: within 2.6e-9 m of the disc of radius 0.05 m about (0.01, 0)."""


def knife(profile: SplineProfile) -> KnifeEdgeCam:
    return KnifeEdgeCam("contact", "cam", profile, Point("follower"), math.pi / 2)


def test_the_sphere_is_a_fraction_of_the_smallest_convex_radius_of_curvature() -> None:
    # The disc's radius of curvature is its radius, everywhere.
    radii = curvature_radii(DISC)
    assert np.allclose(radii, 0.05, rtol=2e-4)
    assert tip_radius(knife(DISC)) == pytest.approx(cam_tip.TIP_FRACTION * 0.05, rel=2e-4)
    assert tip_radius(scenarios.build("cam_knife_edge").cams[0]) == 0.0  # a disc: the box's edge
    assert tip_radius(scenarios.build("cam_roller/spline").cams[0]) == 0.0  # facets on the profile


def test_the_offset_of_a_disc_is_the_concentric_disc_and_the_centre_traces_the_profile() -> None:
    r = tip_radius(knife(DISC))
    offset = vertices(DISC, 512, r)
    # closed form: the inward offset of a circle of radius R by r is the circle of radius R - r
    assert np.abs(np.linalg.norm(offset - [0.01, 0.0], axis=1) - (0.05 - r)).max() < 5e-9
    # the sphere's centre, at each profile point, is r from the offset curve (densely sampled)
    phis = np.linspace(0.0, 2.0 * math.pi, 4096, endpoint=False)
    curve = np.array([offset_point(DISC, float(p), r) for p in phis])
    for phi in np.linspace(0.0, 2.0 * math.pi, 97):
        nearest = np.linalg.norm(curve - offset_point(DISC, float(phi)), axis=1).min()
        assert nearest == pytest.approx(r, rel=1e-6)
    # the polygon's sagitta on that circle: its widest chord, at phi = 0, spans (1 + e / R) 2 pi / N
    # about the disc's centre (the offset keeps the profile point's angle about it)
    widest = (1.0 + 0.01 / 0.05) * 2.0 * math.pi / 256
    assert sagitta(DISC, 256, r) == pytest.approx((0.05 - r) * (1 - math.cos(widest / 2)), rel=1e-3)


def test_a_cam_thinner_than_the_sphere_is_refused_naming_the_sphere() -> None:
    # a waist 12 mm across at phi = +-90 deg, its ends' radius of curvature 18 mm: a 14 mm sphere
    phis = np.linspace(0.0, 2.0 * math.pi, 48, endpoint=False)
    thin = knife(SplineProfile(tuple(0.006 + 0.044 * np.cos(phis) ** 2)))
    reason = tip_reason(thin)
    assert reason is not None and "sphere of radius 0.01444 m" in reason and "thinner" in reason
    assert tip_reason(knife(DISC)) is None


def test_the_spline_knife_edge_runs_ok_within_its_measured_error() -> None:
    # measured 2.6e-6 m, 1.9e-4 m/s, 1.06 m/s^2 at 512 pieces (2.5 s)
    held(follower_errors("cam_knife_edge/spline", DEFAULT_PIECES).tolist(), (2.62e-6, 1.86e-4, 1.06))


@pytest.mark.slow
def test_the_error_falls_with_the_piece_count() -> None:
    counts = (128, 512, 2048)
    errors = np.array([follower_errors("cam_knife_edge/spline", n) for n in counts])
    measured = ((6.02e-6, 3.08e-3, 6.51), (2.62e-6, 1.86e-4, 1.06), (1.28e-6, 9.47e-5, 0.324))
    for found, expected in zip(errors, measured, strict=True):
        held(found.tolist(), expected)
    assert np.all(np.diff(errors, axis=0) < 0.0)


@pytest.mark.slow
def test_the_error_falls_as_the_sphere_nears_the_radius_of_curvature(monkeypatch) -> None:  # type: ignore[no-untyped-def]
    fractions = (0.05, 0.2, 0.8)
    errors = []
    for fraction in fractions:
        monkeypatch.setattr(cam_tip, "TIP_FRACTION", fraction)
        errors.append(follower_errors("cam_knife_edge/spline", DEFAULT_PIECES).tolist())
    measured = ((3.72e-5, 7.44e-2, 509.0), (3.86e-6, 2.66e-3, 16.0), (2.62e-6, 1.86e-4, 1.06))
    for found, expected in zip(errors, measured, strict=True):
        held(found, expected)
    assert np.all(np.diff(np.array(errors), axis=0) < 0.0)
