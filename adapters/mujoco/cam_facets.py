"""A non-circular cam profile as a chain of thin capsules lying in the plane: a polygon of flat facets
MuJoCo collides analytically (capsule-sphere for a roller and for a knife edge's sphere on the
profile's offset, adapters.mujoco.cam_tip; capsule-box for a flat face: the colliders of the disc
cam). Boxes were tried first: a box-box contact between a knife edge or a flat face and a facet
takes the wrong face's normal, and the start does not assemble.

The profile is sampled at `pieces` equally spaced angles; each facet is a capsule of radius
THICKNESS times the smallest radius whose segment is the chord between two consecutive points moved
inward by that radius, so its outer side is the chord; vertices are rounded by that small radius.
The polygon deviates from the profile by the chord's sagitta, about kappa c^2 / 8 for a chord
c = d dphi on a curvature kappa: second order in the piece count. A follower near a vertex touches
the two facets that meet there, as two contact rows of one pair group (adapters.mujoco.assembly
and cam_load group a cam's pairs by their follower geom), which stiffen the contact there.
"""

from __future__ import annotations

import math

import numpy as np

from adapters.mujoco.cam_samples import points_at, radii_at, row_dots, row_norms
from adapters.mujoco.cam_tip import tip_radius
from scenarios.cam_profiles import EccentricDisc, LobedProfile, Profile
from scenarios.cams import CamContact, FlatFaceCam, RollerCam
from scenarios.scenario import Scenario

DEFAULT_PIECES = 512
"""Facets per turn by default, chosen on cam_roller/spline against the native solver: with fewer,
the vertices pass near the soft contact's own frequency and throw the follower off; at 512 the
sagitta is below the contact's own penetration error, and more facets gain less than first order
at several times the run time (the figures: tests/adapters/mujoco/test_cam_facets.py)."""
PIECES_HELP = (
    "facets of a spline cam profile (chords between equally spaced profile points); default 512: the "
    "fewest whose vertices pass above the soft contact's frequency, with a sagitta below the "
    "contact's own error; more facets cost more and gain less than first order"
)
MIN_PIECES = 8
MAX_PIECES = 8192
THICKNESS = 0.01
"""A facet capsule's radius as a fraction of the profile's smallest radius: small, so the rounding
of the polygon's vertices is negligible, yet 20 times the contact's penetration at 100 N."""
SAMPLES = 4096
"""Profile angles sampled for the profile's extent and its smallest radius."""


def extent(profile: Profile) -> tuple[float, float]:
    """The profile's smallest and largest polar radius."""
    phis = np.linspace(0.0, 2.0 * math.pi, SAMPLES, endpoint=False)
    radii = radii_at(profile, phis)[:, 0]
    return float(radii.min()), float(radii.max())


def vertices(profile: Profile, pieces: int, inset: float = 0.0) -> np.ndarray:
    """The polygon's vertices (pieces, 2) in the cam's frame: the profile (or its inward offset by
    `inset`) at equal angles from 0."""
    phis = 2.0 * math.pi * np.arange(pieces) / pieces
    return points_at(profile, phis, inset)


def facets(
    profile: Profile, pieces: int, inset: float = 0.0
) -> tuple[float, list[tuple[float, float, float, float]]]:
    """The facets' capsule radius and, per facet, its segment (x1, y1, x2, y2): the chord moved
    inward by the radius, so that the capsule's outer side is the chord (of the profile, or of its
    inward offset by `inset`)."""
    points = vertices(profile, pieces, inset)
    radius = THICKNESS * extent(profile)[0]
    ends = np.roll(points, -1, axis=0)
    tangents = (ends - points) / np.linalg.norm(ends - points, axis=1)[:, None]
    inward = np.stack([-tangents[:, 1], tangents[:, 0]], axis=1)  # counter-clockwise: left of travel
    starts, stops = points + radius * inward, ends + radius * inward
    pairs = zip(starts.tolist(), stops.tolist(), strict=True)
    return radius, [(a[0], a[1], b[0], b[1]) for a, b in pairs]


def sagitta(profile: Profile, pieces: int, inset: float = 0.0) -> float:
    """The largest distance between the profile (or its inward offset by `inset`) and the chord
    polygon, measured at each chord's middle angle (the faceting's geometric error)."""
    points = vertices(profile, pieces, inset)
    mids = 2.0 * math.pi * (np.arange(pieces) + 0.5) / pieces
    chords = np.roll(points, -1, axis=0) - points
    tangents = chords / row_norms(chords)[:, None]
    outward = np.stack([tangents[:, 1], -tangents[:, 0]], axis=1)
    gaps = np.abs(row_dots(points_at(profile, mids, inset) - points, outward))
    return float(np.max(gaps, initial=0.0, where=~np.isnan(gaps)))  # NaN skipped, as max(0.0, nan)


def lobed_reason(contact: CamContact) -> str | None:
    """Why a lobed cam's concave valleys cannot be faceted for this follower, if they cannot."""
    profile = contact.profile
    if not isinstance(profile, LobedProfile):
        return None
    rho = profile.valley_curvature_radius()
    if rho > 0.0:
        return None
    head = f"cam '{contact.name}' has a lobed profile ({profile.lobes} lobes) with concave valleys"
    if isinstance(contact, RollerCam):
        if contact.roller_radius < -rho:
            return None
        return (
            f"{head} of radius {-rho:.4g} m, narrower than the {contact.roller_radius:.4g} m roller: "
            "the roller would touch both flanks and undercut the profile"
        )
    if isinstance(contact, FlatFaceCam):
        return f"{head}: a flat face bridges a concave valley and never touches its bottom"
    return None  # a knife edge's sphere runs on the offset, whose valleys are wider (adapters.mujoco.cam_tip)


def faceted(scenario: Scenario) -> bool:
    """Whether some cam of the scenario is built as facets (a profile other than a disc)."""
    return any(not isinstance(c.profile, EccentricDisc) for c in scenario.cams)


def hops(contacts: tuple[CamContact, ...], pieces: int) -> dict[int, float]:
    """Per faceted cam (its index among the contacts): its polygon's sagitta, the gap its follower
    may show where it hops off a vertex (adapters.mujoco.cam_load.check_contacts)."""
    faceted = [(k, c) for k, c in enumerate(contacts) if not isinstance(c.profile, EccentricDisc)]
    return {k: sagitta(c.profile, pieces, tip_radius(c)) for k, c in faceted}
