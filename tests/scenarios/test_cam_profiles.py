"""The cam profiles' values, where derivative checks cannot see them: a lobed cam's radius of
curvature at a valley's bottom against the curvature of its curve measured by central differences of
points computed here from d = r + a cos(n phi); a tabulated profile's table, its spline through the
table on every turn and its convergence to the profile it samples; the profile point u(phi) and its
derivatives. (Profiles built at a test module's import are never mutated under mutmut, which imports
the tests before planting: each profile here is built inside its test.)"""

from __future__ import annotations

import math

import numpy as np
import pytest

from scenarios.cam_profiles import EccentricDisc, LobedProfile, Profile, SplineProfile, profile_point

STEP = 1e-4


def _radius_of_curvature(r: float, a: float, n: int, phi: float) -> float:
    """Signed radius of curvature of the curve d(phi) [cos phi, sin phi] at phi, from second-order
    central differences of its points (positive where it turns left, as the convex disc does)."""

    def point(p: float) -> tuple[float, float]:
        d = r + a * math.cos(n * p)
        return d * math.cos(p), d * math.sin(p)

    (xb, yb), (x0, y0), (xa, ya) = point(phi - STEP), point(phi), point(phi + STEP)
    dx, dy = (xa - xb) / (2 * STEP), (ya - yb) / (2 * STEP)
    ddx, ddy = (xa - 2 * x0 + xb) / STEP**2, (ya - 2 * y0 + yb) / STEP**2
    return (dx * dx + dy * dy) ** 1.5 / (dx * ddy - dy * ddx)


@pytest.mark.parametrize(
    ("radius", "amplitude", "lobes", "convex"),
    [(0.05, 0.004, 3, True), (0.04, 0.002, 7, False), (0.03, 0.001, 2, True)],
)
def test_the_valley_s_radius_of_curvature_is_the_profile_curve_s(
    radius: float, amplitude: float, lobes: int, convex: bool
) -> None:
    profile = LobedProfile(radius=radius, amplitude=amplitude, lobes=lobes)
    measured = _radius_of_curvature(radius, amplitude, lobes, math.pi / lobes)
    assert (measured > 0) is convex
    assert profile.valley_curvature_radius() == pytest.approx(measured, rel=1e-6)


DISC = EccentricDisc(radius=0.05, eccentricity=0.01)


def _disc_radius(phi: float) -> float:
    """The disc's polar radius written out: the centre e along x, the circle of radius R about it."""
    e, r = DISC.eccentricity, DISC.radius
    return e * math.cos(phi) + math.sqrt(r * r - (e * math.sin(phi)) ** 2)


def test_a_sampled_profile_tabulates_the_radius_at_equal_angles_from_zero() -> None:
    table = SplineProfile.sample(DISC, 8).table
    assert table == pytest.approx([_disc_radius(2 * math.pi * k / 8) for k in range(8)], abs=1e-15)


@pytest.mark.parametrize("turns", [-2, -1, 0, 1, 3])
def test_a_spline_profile_passes_through_its_table_on_every_turn(turns: int) -> None:
    """At the k-th knot, on any turn (negative angles and beyond 2 pi included), d is table[k]."""
    table = tuple(0.05 + 0.004 * math.cos(3 * 2 * math.pi * k / 12) + 0.001 * k / 12 for k in range(12))
    profile = SplineProfile(table)
    for k, value in enumerate(table):
        phi = 2 * math.pi * (k / 12 + turns)
        assert profile.radii(phi)[0] == pytest.approx(value, abs=1e-14), (k, turns)


def test_a_fine_spline_of_the_disc_converges_to_the_disc_at_each_derivative() -> None:
    """A periodic cubic spline of knot spacing h is off by O(h^4) in d, O(h^3) in d', O(h^2) in d''
    and O(h) in d''' (piecewise constant): 720 knots (h = 0.0087) against the disc's closed form at
    random angles over four turns, both signs; each bound is a few times the order's estimate e h^k."""
    profile = SplineProfile.sample(DISC, 720)
    h, e = 2 * math.pi / 720, DISC.eccentricity
    rng = np.random.default_rng(41)
    for phi in rng.uniform(-4 * math.pi, 4 * math.pi, 50):
        d = profile.radii(float(phi))
        exact = DISC.radii(float(phi))
        assert d[0] == pytest.approx(_disc_radius(phi), abs=e * h**4)
        for k, bound in ((1, e * h**3), (2, e * h**2), (3, 2 * e * h)):
            assert abs(d[k] - exact[k]) < bound, (phi, k)


@pytest.mark.parametrize(
    "profile", [DISC, LobedProfile(radius=0.05, amplitude=0.005, lobes=3)], ids=["disc", "lobed"]
)
def test_the_profile_point_and_its_derivatives_are_the_curve_s(profile: Profile) -> None:
    """u = d (cos phi, sin phi) from the radius alone; u', u'', u''' against central differences of
    the level below, at random angles."""
    step = 1e-5
    rng = np.random.default_rng(7)
    for phi in rng.uniform(-2 * math.pi, 4 * math.pi, 40):
        u = profile_point(profile, float(phi))
        d = profile.radii(float(phi))[0]
        assert u[0] == pytest.approx([d * math.cos(phi), d * math.sin(phi)], abs=1e-15)
        above, below = profile_point(profile, phi + step), profile_point(profile, phi - step)
        for k in (1, 2, 3):
            difference = (above[k - 1] - below[k - 1]) / (2 * step)
            scale = max(float(np.max(np.abs(u[k]))), 1e-3)
            assert np.max(np.abs(difference - u[k])) < 1e-7 * scale, (phi, k)


def test_a_spline_profile_just_below_zero_and_at_zero_is_its_first_knot_s() -> None:
    """-1e-300 rad wraps to 2 pi itself in floating point, the end of the last piece: d is still
    table[0]. At phi = 0 and -2 pi, d''' (constant on each piece) is the first piece's, as just after
    the knot: each piece holds from its left knot."""
    table = tuple(0.05 + 0.004 * math.cos(3 * 2 * math.pi * k / 12) + 0.001 * k / 12 for k in range(12))
    profile = SplineProfile(table)
    assert profile.radii(-1e-300)[0] == pytest.approx(table[0], abs=1e-14)
    after = profile.radii(1e-9)[3]
    assert profile.radii(0.0)[3] == after and profile.radii(-2 * math.pi)[3] == after
    assert profile.radii(-1e-9)[3] != after  # the last piece's: d''' does jump at the knot
