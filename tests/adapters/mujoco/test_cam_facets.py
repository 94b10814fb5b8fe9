"""MuJoCo's faceted cams: the chord polygon's geometry, the spline cams run ok against the native
solver, the error falls with the piece count, and what stays refused says why (the knife edge, a
sphere on the profile's offset: test_cam_tip).

Measured with MuJoCo 4.0 at the rule's default (RK4, dt = 1/2000 of the cam's turn, tc 4 steps,
contact solimp 0.99, preload 100 N), follower errors against the native solver (m, m/s, m/s^2;
total wall time of one run, build included):

    cam_roller/spline   pieces  sagitta   position  velocity  acceleration  time
                          32    3.5e-4    3.6e-4    1.2e-1    5.1e2         0.15 s
                          64    8.7e-5    1.3e-4    7.1e-2    5.0e2         0.19 s
                         128    2.2e-5    6.5e-5    8.8e-2    5.1e2         0.27 s
                         256    5.4e-6    5.1e-5    6.0e-2    5.1e2         0.43 s
                         512    1.4e-6    3.9e-6    2.4e-3    1.5e1         0.75 s
                        1024    3.4e-7    2.2e-6    1.6e-3    7.6           1.40 s
                        2048    8.5e-8    1.3e-6    1.0e-3    5.3           2.68 s
                        4096    2.1e-8    9.2e-7    5.4e-4    3.4           5.61 s
    cam_flat_face/spline 512              2.3e-6    1.4e-3    6.5           2.36 s
                        1024              1.3e-6    4.2e-4    2.8           4.64 s
                        2048              8.1e-7    3.4e-4    1.5           9.28 s

The flat face's times are from before it collided by bits (adapters.mujoco.cams), which made its
steps about 5 times cheaper with the same errors.

Below 512 pieces the vertices pass at 100-400 Hz, near the soft contact's own frequency (tc =
1.3e-3 s), and the follower is thrown off them (accelerations of 500 m/s^2, the preload over the
mass). From 512 up, errors fall at order 0.8 (position) and 0.6-0.8 (velocity, acceleration) in
the piece count, not the sagitta's 2: the soft contact's penetration (9e-6 m on the disc cam) and
the facets' kinks, not the sagitta, set the error there.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import scenarios
from adapters.base import Setting
from adapters.mujoco.cam_facets import DEFAULT_PIECES, facets, sagitta, vertices
from scenarios.cam_profiles import EccentricDisc, SplineProfile
from tests.support.mujoco.cam_follower import ADAPTER, follower_errors


def test_the_sagitta_is_second_order_and_the_capsules_outer_sides_are_the_chords() -> None:
    profile = SplineProfile.sample(EccentricDisc(0.05, 0.01), 72)
    coarse, fine = sagitta(profile, 128), sagitta(profile, 256)
    assert math.log2(coarse / fine) == pytest.approx(2.0, abs=0.05)
    # The circle's own: R (1 - cos(pi / N)) for a centred disc.
    circle = SplineProfile.sample(EccentricDisc(0.05, 0.0), 72)
    assert sagitta(circle, 64) == pytest.approx(0.05 * (1 - math.cos(math.pi / 64)), rel=1e-3)
    radius, segments = facets(profile, 64)
    points = vertices(profile, 64)
    for k, (x1, y1, x2, y2) in enumerate(segments):
        a, b = np.array([x1, y1]), np.array([x2, y2])
        tangent = (b - a) / np.linalg.norm(b - a)
        outward = np.array([tangent[1], -tangent[0]])
        assert np.allclose(a + radius * outward, points[k], atol=1e-15)
        assert np.allclose(b + radius * outward, points[(k + 1) % 64], atol=1e-15)


def test_the_default_setting_carries_the_piece_count_only_for_faceted_cams() -> None:
    assert ADAPTER.default_setting(scenarios.build("cam_roller/spline"))["cam_pieces"] == DEFAULT_PIECES
    assert ADAPTER.default_setting(scenarios.build("cam_roller")).get("cam_pieces") is None
    xml = ADAPTER.build(scenarios.build("cam_roller/spline"), Setting.of("RK4", cam_pieces=16)).xml
    assert xml.count("<pair ") == 16


def test_the_spline_roller_runs_ok_within_its_measured_error() -> None:
    # measured 3.9e-6 m, 2.4e-3 m/s, 15 m/s^2 at 512 pieces
    position, velocity, acceleration = follower_errors("cam_roller/spline", DEFAULT_PIECES)
    assert position < 1e-5 and velocity < 6e-3 and acceleration < 40.0


@pytest.mark.slow
def test_the_spline_flat_face_runs_ok_within_its_measured_error() -> None:
    # measured 2.3e-6 m, 1.4e-3 m/s, 6.5 m/s^2 at 512 pieces (2.4 s)
    position, velocity, acceleration = follower_errors("cam_flat_face/spline", DEFAULT_PIECES)
    assert position < 7e-6 and velocity < 4e-3 and acceleration < 20.0


@pytest.mark.slow
def test_the_error_falls_with_the_piece_count_at_its_measured_order() -> None:
    counts = (512, 1024, 2048)
    errors = np.array([follower_errors("cam_roller/spline", n) for n in counts])
    orders = np.log2(errors[0] / errors[-1]) / math.log2(counts[-1] / counts[0])
    # measured orders 0.80 (position), 0.63 (velocity), 0.74 (acceleration)
    assert orders[0] > 0.5 and orders[1] > 0.4 and orders[2] > 0.4
    assert np.all(errors[:, 0] < 3.0 * np.array([3.9e-6, 2.2e-6, 1.3e-6]))


@pytest.mark.parametrize(
    ("name", "overrides", "words"),
    [
        ("cam_roller", {"profile": "lobed", "roller_radius": 0.04}, "narrower than the 0.04 m roller"),
        ("cam_flat_face", {"profile": "lobed"}, "bridges a concave valley"),
    ],
)
def test_lobed_cams_are_refused_naming_valleys_the_follower_cannot_follow(
    name: str, overrides: dict[str, object], words: str
) -> None:
    reason = ADAPTER.supports(scenarios.build(name, overrides=overrides))  # type: ignore[arg-type]
    assert reason is not None and "concave valleys" in reason and words in reason


@pytest.mark.parametrize("name", ["cam_roller", "cam_knife_edge"])
def test_other_lobed_cams_are_refused_with_the_measured_chatter(name: str) -> None:
    reason = ADAPTER.supports(scenarios.build(name, overrides={"profile": "lobed"}))
    assert reason is not None and "a lobed profile" in reason and "chatters" in reason
