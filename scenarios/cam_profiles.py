"""Cam profiles in polar form about the cam's centre of rotation: u(phi) = d(phi) [cos phi, sin phi].

A profile supplies d and its first three derivatives in phi; the third is needed by the acceleration
right-hand side of the roller and flat-faced contacts.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:  # scipy.interpolate is imported by the first tabulated profile's spline only
    from scipy.interpolate import CubicSpline


@dataclass(frozen=True)
class EccentricDisc:
    """A circular disc of `radius` whose centre is `eccentricity` from the rotation centre, along the
    cam frame's x axis. Polar form: d(phi) = e cos phi + sqrt(R^2 - e^2 sin^2 phi)."""

    radius: float
    eccentricity: float

    def radii(self, phi: float) -> tuple[float, float, float, float]:
        """d(phi) and its first three derivatives."""
        return disc_radii(self.radius, self.eccentricity, phi)


@dataclass(frozen=True)
class SplineProfile:
    """A periodic cubic spline through radii tabulated at equally spaced angles over one turn."""

    table: tuple[float, ...]

    @classmethod
    def sample(cls, profile: EccentricDisc, knots: int) -> SplineProfile:
        """Tabulate another profile's radius at `knots` equally spaced angles."""
        phis = np.linspace(0.0, 2.0 * math.pi, knots, endpoint=False)
        return cls(tuple(float(profile.radii(float(p))[0]) for p in phis))

    @cached_property
    def spline(self) -> CubicSpline:
        """The periodic cubic spline through the table (scipy), closed at 2 pi."""
        from scipy.interpolate import CubicSpline

        n = len(self.table)
        phis = np.linspace(0.0, 2.0 * math.pi, n + 1)
        values = np.append(np.asarray(self.table), self.table[0])
        return CubicSpline(phis, values, bc_type="periodic")

    @cached_property
    def pieces(self) -> tuple[tuple[float, float, float, float], ...]:
        """Per interval (equal widths from phi = 0), the local cubic's coefficients at its left
        knot: d, d', d''/2 and d'''/6."""
        c = self.spline.c
        return tuple(
            (float(c[3, k]), float(c[2, k]), float(c[1, k]), float(c[0, k])) for k in range(c.shape[1])
        )

    def radii(self, phi: float) -> tuple[float, float, float, float]:
        """d(phi) and its first three derivatives (the third is piecewise constant)."""
        pieces = self.pieces
        width = 2.0 * math.pi / len(pieces)
        p = math.fmod(phi, 2.0 * math.pi)
        if p < 0.0:
            p += 2.0 * math.pi
        k = min(int(p / width), len(pieces) - 1)
        x = p - k * width
        c0, c1, c2, c3 = pieces[k]
        return (
            c0 + x * (c1 + x * (c2 + x * c3)),
            c1 + x * (2.0 * c2 + 3.0 * c3 * x),
            2.0 * c2 + 6.0 * c3 * x,
            6.0 * c3,
        )


@dataclass(frozen=True)
class LobedProfile:
    """A cam of `lobes` equal lobes: d(phi) = radius + amplitude cos(lobes phi), peaks at phi = 0.

    Its curvature varies along the profile and its valleys are concave once amplitude * lobes^2
    exceeds radius - amplitude; the concave radius of curvature at a valley's bottom is
    (radius - amplitude)^2 / (amplitude lobes^2 - radius + amplitude), the largest roller that
    does not undercut it.
    """

    radius: float
    amplitude: float
    lobes: int

    def radii(self, phi: float) -> tuple[float, float, float, float]:
        """d(phi) and its first three derivatives."""
        return lobed_radii(self.radius, self.amplitude, self.lobes, phi)

    def valley_curvature_radius(self) -> float:
        """The radius of curvature at a valley's bottom: positive if convex, negative if concave."""
        d = self.radius - self.amplitude
        return d * d / (d - self.amplitude * self.lobes**2)


Profile = EccentricDisc | SplineProfile | LobedProfile


def profile_point(profile: Profile, phi: float) -> np.ndarray:
    """The local point u(phi) and its derivatives u', u'', u''' as rows of a (4, 2) array."""
    d0, d1, d2, d3 = profile.radii(phi)
    c, s = math.cos(phi), math.sin(phi)
    radial = np.array([c, s])
    normal = np.array([-s, c])
    # Derivatives of d(phi) e_r(phi), with e_r' = e_n and e_n' = -e_r.
    return np.array(
        [
            d0 * radial,
            d1 * radial + d0 * normal,
            (d2 - d0) * radial + 2.0 * d1 * normal,
            (d3 - 3.0 * d1) * radial + (3.0 * d2 - d0) * normal,
        ]
    )


def disc_radii(r: float, e: float, phi: float) -> tuple[float, float, float, float]:
    """An eccentric disc's d(phi) and its first three derivatives (radius r, eccentricity e). Plain
    float arithmetic, so that the compiled path (reference_solver.compiled.evaluate) compiles this very
    function instead of restating it."""
    s2, c2 = math.sin(2.0 * phi), math.cos(2.0 * phi)
    sn = math.sin(phi)
    cs = math.cos(phi)
    s = r * r - e * e * sn * sn
    s1 = -e * e * s2
    s2d = -2.0 * e * e * c2
    s3d = 4.0 * e * e * s2
    g = math.sqrt(s)
    g1 = s1 / (2.0 * g)
    g2 = s2d / (2.0 * g) - s1 * s1 / (4.0 * g**3)
    g3 = (
        s3d / (2.0 * g)
        - s2d * g1 / (2.0 * g * g)
        - s1 * s2d / (2.0 * g**3)
        + 3.0 * s1 * s1 * g1 / (4.0 * g**4)
    )
    return e * cs + g, -e * sn + g1, -e * cs + g2, e * sn + g3


def lobed_radii(r: float, a: float, n: float, phi: float) -> tuple[float, float, float, float]:
    """A lobed cam's d(phi) = r + a cos(n phi) and its first three derivatives (compiled as is by
    the compiled path, like disc_radii)."""
    c, s = math.cos(n * phi), math.sin(n * phi)
    return r + a * c, -a * n * s, -a * n * n * c, a * n**3 * s
