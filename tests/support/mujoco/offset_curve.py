"""A point of a cam profile's inward offset curve, built one angle at a time from the profile's own
point and tangent (scenarios.cam_profiles.profile_point): the construction the MuJoCo adapter's array
forms (adapters.mujoco.cam_samples.points_at) replaced and are checked against, and an independent
curve for the knife edge's tip sphere (test_cam_tip.py)."""

from __future__ import annotations

import numpy as np

from scenarios.cam_profiles import Profile, profile_point


def offset_point(profile: Profile, phi: float, inset: float = 0.0) -> np.ndarray:
    """The profile's point at polar angle phi moved inward along its normal by `inset`: a point of
    its inward offset curve (0: of the profile itself)."""
    u = profile_point(profile, phi)
    if inset == 0.0:
        return u[0]
    tangent = u[1] / np.linalg.norm(u[1])
    return u[0] + inset * np.array([-tangent[1], tangent[0]])  # left of travel: inward
