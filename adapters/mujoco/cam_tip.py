"""A knife edge on a faceted cam as a small sphere running on the profile's inward offset.

A knife edge's tip is a point on the profile, and a polygon of facets turns its velocity at every
vertex: the tip is thrown off each one and chatters. A sphere of radius r whose centre is the tip,
running on the profile's inward offset curve by r, has its centre on the offset of that offset by r,
which is the profile itself wherever r is below the profile's smallest convex radius of curvature
(a concave part's offset only grows its radius: |rho| + r): the centre traces exactly the knife's
path, and the contact normal through it is the profile's normal at the tip, so the follower's
motion and contact force are the knife edge's, with nothing to take out of its lift. What is left
is the roller's faceting error, on the offset polygon instead of the profile's.
"""

from __future__ import annotations

import math

import numpy as np

from scenarios.cam_profiles import EccentricDisc, Profile
from scenarios.cams import CamContact, KnifeEdgeCam

TIP_FRACTION = 0.4
"""The sphere's radius as a fraction of the profile's smallest convex radius of curvature."""
SAMPLES = 4096
"""Profile angles sampled for the smallest radius of curvature."""


def curvature_radii(profile: Profile) -> np.ndarray:
    """The profile's signed radius of curvature at SAMPLES equal angles (positive where convex):
    (d^2 + d'^2)^(3/2) / (d^2 + 2 d'^2 - d d'')."""
    phis = np.linspace(0.0, 2.0 * math.pi, SAMPLES, endpoint=False)
    d = np.array([profile.radii(float(p))[:3] for p in phis])
    speed = (d[:, 0] ** 2 + d[:, 1] ** 2) ** 1.5
    bend = d[:, 0] ** 2 + 2.0 * d[:, 1] ** 2 - d[:, 0] * d[:, 2]
    with np.errstate(divide="ignore"):
        return np.where(bend != 0.0, speed / bend, np.inf)


def tip_radius(contact: CamContact) -> float:
    """The sphere's radius for a knife edge on a faceted profile (0 for every other contact: its
    facets lie on the profile itself)."""
    if not isinstance(contact, KnifeEdgeCam) or isinstance(contact.profile, EccentricDisc):
        return 0.0
    radii = curvature_radii(contact.profile)
    convex = radii[radii > 0.0]
    return TIP_FRACTION * float(convex.min())
