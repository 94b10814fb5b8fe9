"""The cam contacts' residuals at a hand-worked contact.

The profile is an eccentric disc of radius 5 whose centre is 3 from the cam's rotation centre, along
the cam's x axis. At phi = pi/2 the profile point is on the cam's y axis, 4 from the rotation centre
(a 3-4-5 triangle): u = (0, 4). The tangent u' = d' e_r + d e_n, with d(phi) = e cos phi +
sqrt(R^2 - e^2 sin^2 phi), so d'(pi/2) = -3: u' = -3 (0, 1) + 4 (-1, 0) = (-4, -3), square to the
disc's radius (-3, 4) there; the outward normal is (-3, 4)/5.
"""

from __future__ import annotations

import math

import numpy as np

from scenarios import EccentricDisc, FlatFaceCam, KnifeEdgeCam, Point, RollerCam
from tests.support.constraint_systems import residual, system_of

DISC = EccentricDisc(5.0, 3.0)
CONTACT = (math.pi / 2,)  # phi
CAM_TURNED = {"a": (1.0, 1.0, math.pi / 2)}  # u = (0, 4) at (1, 1) + (-4, 0); the tangent (3, -4)


def test_a_knife_edge_is_the_gap_from_the_profile_point_to_the_tip() -> None:
    cam = KnifeEdgeCam("k", "a", DISC, Point("b", (0.5, 0.0)), 0.0)
    c = residual(cam, {**CAM_TURNED, "b": (-3.5, 1.5, 0.0)}, phis=CONTACT)  # the tip at (-3, 1.5)
    np.testing.assert_allclose(c, [0.0, -0.5], rtol=0, atol=1e-14)


def test_a_roller_is_its_centre_off_the_normal_and_its_squared_distance_less_its_radius_squared() -> None:
    """The centre 0.4 * 5 = 2 out along the normal and 0.1 * 5 along the tangent from the contact:
    n = 0.4 (-3, 4) + 0.1 (-4, -3), so n . t = 0.1 * 25 and n . n = 0.16 * 25 + 0.01 * 25, against
    a roller of radius 1.5 (the cam unturned at the origin; not 2, whose square is also its double)."""
    cam = RollerCam("k", "a", DISC, Point("b", (0.0, 0.3)), 1.5, 0.0)
    centre = (0.4 * -3 + 0.1 * -4, 4 + 0.4 * 4 + 0.1 * -3)
    c = residual(cam, {"b": (centre[0], centre[1] - 0.3, 0.0)}, phis=CONTACT)
    np.testing.assert_allclose(c, [2.5, 4.25 - 1.5**2], rtol=0, atol=1e-14)


def test_a_flat_face_is_the_tangent_across_its_normal_and_the_profile_point_off_the_face() -> None:
    """The face's normal (3, 4) (not unit) on b turned by 90 degrees points along (-4, 3)/5; the face
    point (1, 0.5) on b at (0, 5) is at (-0.5, 6). The cam turned as above: u at (-3, 1), tangent
    (3, -4): h . t = (-12 - 12)/5 and h . (r_cam - r_face) = h . (-2.5, -5) = (10 - 15)/5."""
    cam = FlatFaceCam("k", "a", DISC, Point("b", (1.0, 0.5)), (3.0, 4.0), 0.0)
    c = residual(cam, {**CAM_TURNED, "b": (0.0, 5.0, math.pi / 2)}, phis=CONTACT)
    np.testing.assert_allclose(c, [-24 / 5, -1.0], rtol=0, atol=1e-14)


def test_each_cam_row_is_named_after_its_contact_and_what_it_constrains() -> None:
    system = system_of(
        KnifeEdgeCam("ke", "a", DISC, Point("b"), 0.0),
        RollerCam("ro", "a", DISC, Point("b"), 1.0, 0.0),
        FlatFaceCam("ff", "a", DISC, Point("c"), (0.0, 1.0), 0.0),
    )
    assert system.labels == ["ke.x", "ke.y", "ro.tangent", "ro.distance", "ff.tangent", "ff.distance"]
    assert [e.name for e in system.equations] == ["ke", "ro", "ff"]
