"""A knife edge on a faceted cam as a sphere running on the profile's inward offset curve.

A knife edge's tip is a point on the profile, and a polygon of facets turns its velocity at every
vertex: the tip is thrown off each one and chatters (acceleration errors of 510 m/s^2 on
cam_knife_edge/spline from 256 to 2048 facets, the preload over the mass). Instead the tip is a
sphere of radius r centred on it, rolling on the facets of the profile's inward offset curve by r
(points: adapters.mujoco.cam_samples.points_at with `inset`; facets: adapters.mujoco.cam_facets with
`inset`). The sphere's centre runs on the outward offset of that curve by r, which is the profile
itself wherever a disc of radius r rolls inside the profile touching every point of it: r below the
smallest convex radius of curvature (a concave part's offset only grows its radius, to |rho| + r)
and no part of the cam thinner than 2r (checked: `tip_reason`). So the centre traces exactly the
knife's path, and the contact normal through it is the profile's normal at the tip: the follower's
lift and its contact force are the knife edge's, with nothing to take out. What is left is a
roller's faceting error on the offset polygon, which falls as r nears the smallest radius of
curvature rho (on a circle the offset shrinks to a point at r = rho, where the sphere is exact):
measured on cam_knife_edge/spline at 512 facets, acceleration errors 510, 66, 16, 7.4, 2.8, 1.1
m/s^2 at r = 0.05, 0.1, 0.2, 0.4, 0.6, 0.8 rho (tests/adapters/mujoco/test_cam_tip.py).
"""

from __future__ import annotations

import math

import numpy as np

from adapters.mujoco.cam_samples import nearest_distance, points_at, radii_at
from scenarios.cam_profiles import EccentricDisc, Profile
from scenarios.cams import CamContact, KnifeEdgeCam

TIP_FRACTION = 0.8
"""The sphere's radius as a fraction of the profile's smallest convex radius of curvature: large,
since the error falls as the fraction nears 1, yet leaving the offset curve a fifth of that radius
(50 times the facets' capsule radius, adapters.mujoco.cam_facets.THICKNESS, on the spline cams)."""
SAMPLES = 4096
"""Profile angles sampled for the smallest radius of curvature."""
CHECKS = 1024
"""Profile and offset points compared for a part of the cam thinner than the sphere."""
UNDERCUT = 1e-3
"""A profile point nearer the offset curve than (1 - UNDERCUT) r is undercut."""


def curvature_radii(profile: Profile, samples: int = SAMPLES) -> np.ndarray:
    """The profile's signed radius of curvature at `samples` equal angles, positive where convex:
    (d^2 + d'^2)^(3/2) / (d^2 + 2 d'^2 - d d'') for the polar profile d(phi)."""
    phis = np.linspace(0.0, 2.0 * math.pi, samples, endpoint=False)
    d = radii_at(profile, phis)[:, :3]
    speed = (d[:, 0] ** 2 + d[:, 1] ** 2) ** 1.5
    bend = d[:, 0] ** 2 + 2.0 * d[:, 1] ** 2 - d[:, 0] * d[:, 2]
    with np.errstate(divide="ignore"):
        return np.where(bend != 0.0, speed / bend, np.inf)


def tip_radius(contact: CamContact) -> float:
    """The sphere's radius for a knife edge on a faceted profile; 0 for every other contact (a disc
    cam's knife edge is a box's edge, and a roller's or flat face's facets lie on the profile)."""
    if not isinstance(contact, KnifeEdgeCam) or isinstance(contact.profile, EccentricDisc):
        return 0.0
    radii = curvature_radii(contact.profile)
    return TIP_FRACTION * float(radii[radii > 0.0].min())


def tip_reason(contact: CamContact) -> str | None:
    """Why the sphere would not trace the knife's path on this profile, if it would not: some
    profile point nearer the offset curve than r, where the cam is thinner than the sphere."""
    r = tip_radius(contact)
    if r == 0.0:
        return None
    phis = np.linspace(0.0, 2.0 * math.pi, CHECKS, endpoint=False)
    nearest = nearest_distance(points_at(contact.profile, phis), points_at(contact.profile, phis, r))
    if nearest >= (1.0 - UNDERCUT) * r:
        return None
    return (
        f"cam '{contact.name}': MuJoCo's knife edge on a faceted profile is a sphere of radius "
        f"{r:.4g} m ({TIP_FRACTION:g} of the smallest convex radius of curvature) on the profile's "
        f"offset by it, and part of the cam is thinner than that sphere (a profile point "
        f"{nearest:.4g} m from the offset): the sphere would not trace the knife's path"
    )
