"""The MuJoCo build's array forms against the per-angle construction they replaced, for equality (not
closeness): a faceted cam's profile samples, facets, sagitta, tip sphere and its check
(adapters.mujoco.cam_samples and its users), and the facets as the MJCF text carries them. The
construction kept here is the code of the build before it became arrays: one Python call per angle
and per facet, np.linalg.norm and `@` on single vectors."""

from __future__ import annotations

import math
from dataclasses import replace

import mujoco
import numpy as np
import pytest

import scenarios
from adapters.mujoco import MujocoAdapter
from adapters.mujoco.cam_facets import THICKNESS, extent, facets, hops, sagitta, vertices
from adapters.mujoco.cam_samples import nearest_distance, points_at, radii_at, row_dots, row_norms
from adapters.mujoco.cam_tip import CHECKS, SAMPLES, curvature_radii, tip_radius, tip_reason
from adapters.mujoco.equalities import num
from scenarios.cam_profiles import EccentricDisc, Profile, SplineProfile
from scenarios.cams import CamContact
from tests.support.mujoco.offset_curve import offset_point

SPLINE_SCENES = ("cam_roller/spline", "cam_flat_face/spline", "cam_knife_edge/spline")
ADAPTER = MujocoAdapter()


def same(a: np.ndarray, b: np.ndarray) -> bool:
    """Equal bit for bit (shape, dtype and every byte)."""
    a, b = np.asarray(a), np.asarray(b)
    return a.shape == b.shape and a.dtype == b.dtype and a.tobytes() == b.tobytes()


def contacts() -> list[CamContact]:
    return [scenarios.build(name).cams[0] for name in SPLINE_SCENES]


# --- the per-angle construction the build used before --------------------------------------------


def old_extent(profile: Profile) -> tuple[float, float]:
    phis = np.linspace(0.0, 2.0 * math.pi, 4096, endpoint=False)
    radii = np.array([profile.radii(float(p))[0] for p in phis])
    return float(radii.min()), float(radii.max())


def old_vertices(profile: Profile, pieces: int, inset: float = 0.0) -> np.ndarray:
    phis = 2.0 * math.pi * np.arange(pieces) / pieces
    return np.array([offset_point(profile, float(p), inset) for p in phis])


def old_facets(profile: Profile, pieces: int, inset: float) -> tuple[float, list[tuple[float, ...]]]:
    points = old_vertices(profile, pieces, inset)
    radius = THICKNESS * old_extent(profile)[0]
    ends = np.roll(points, -1, axis=0)
    tangents = (ends - points) / np.linalg.norm(ends - points, axis=1)[:, None]
    inward = np.stack([-tangents[:, 1], tangents[:, 0]], axis=1)
    starts, stops = points + radius * inward, ends + radius * inward
    return radius, [(a[0], a[1], b[0], b[1]) for a, b in zip(starts.tolist(), stops.tolist(), strict=True)]


def old_sagitta(profile: Profile, pieces: int, inset: float = 0.0) -> float:
    points = old_vertices(profile, pieces, inset)
    mids = 2.0 * math.pi * (np.arange(pieces) + 0.5) / pieces
    worst = 0.0
    for k, phi in enumerate(mids):
        a, b = points[k], points[(k + 1) % pieces]
        tangent = (b - a) / np.linalg.norm(b - a)
        outward = np.array([tangent[1], -tangent[0]])
        worst = max(worst, abs(float((offset_point(profile, float(phi), inset) - a) @ outward)))
    return worst


def old_curvature_radii(profile: Profile) -> np.ndarray:
    phis = np.linspace(0.0, 2.0 * math.pi, SAMPLES, endpoint=False)
    d = np.array([profile.radii(float(p))[:3] for p in phis])
    speed = (d[:, 0] ** 2 + d[:, 1] ** 2) ** 1.5
    bend = d[:, 0] ** 2 + 2.0 * d[:, 1] ** 2 - d[:, 0] * d[:, 2]
    with np.errstate(divide="ignore"):
        return np.where(bend != 0.0, speed / bend, np.inf)


def old_nearest(profile: Profile, r: float) -> float:
    phis = np.linspace(0.0, 2.0 * math.pi, CHECKS, endpoint=False)
    points = np.array([offset_point(profile, float(p)) for p in phis])
    offset = np.array([offset_point(profile, float(p), r) for p in phis])
    return min(float(np.linalg.norm(offset - p, axis=1).min()) for p in points)


# --- the array forms ------------------------------------------------------------------------------


@pytest.mark.parametrize("contact", contacts(), ids=SPLINE_SCENES)
def test_profile_samples_are_the_per_angle_values(contact: CamContact) -> None:
    profile = contact.profile
    phis = np.concatenate([np.linspace(-7.0, 13.0, 2001), 2.0 * math.pi * np.arange(64) / 64])
    assert same(radii_at(profile, phis), np.array([profile.radii(float(p)) for p in phis]))
    for inset in (0.0, 0.8 * 0.05):
        expected = np.array([offset_point(profile, float(p), inset) for p in phis])
        assert same(points_at(profile, phis, inset), expected)


def test_a_closed_form_profile_is_sampled_per_angle() -> None:
    disc = EccentricDisc(0.05, 0.01)
    phis = np.linspace(0.0, 7.0, 33)
    assert same(radii_at(disc, phis), np.array([disc.radii(float(p)) for p in phis]))
    assert same(points_at(disc, phis, 0.01), np.array([offset_point(disc, float(p), 0.01) for p in phis]))


def test_row_norms_and_dots_are_those_of_single_vectors() -> None:
    # np.linalg.norm and `@` on one vector go through BLAS's dot, which may fuse a multiply-add: a
    # sum of squares differs from it in the last bit for some vectors, the stacked matmul does not.
    rng = np.random.default_rng(27)
    a = rng.normal(size=(4000, 2)) * rng.uniform(1e-3, 1e3, size=(4000, 1))
    b = rng.normal(size=(4000, 2))
    assert same(row_norms(a), np.array([np.linalg.norm(v) for v in a]))
    assert same(row_dots(a, b), np.array([u @ v for u, v in zip(a, b, strict=True)]))
    assert nearest_distance(a[:300], b[:500]) == min(
        float(np.linalg.norm(b[:500] - p, axis=1).min()) for p in a[:300]
    )


@pytest.mark.parametrize("contact", contacts(), ids=SPLINE_SCENES)
def test_facets_sagitta_and_tip_are_the_per_piece_construction(contact: CamContact) -> None:
    profile, r = contact.profile, tip_radius(contact)
    assert extent(profile) == old_extent(profile)
    assert same(vertices(profile, 512, r), old_vertices(profile, 512, r))
    assert facets(profile, 512, r) == old_facets(profile, 512, r)
    assert sagitta(profile, 512, r) == old_sagitta(profile, 512, r)
    assert hops((contact,), 512) == {0: old_sagitta(profile, 512, r)}
    assert same(curvature_radii(profile), old_curvature_radii(profile))
    if r > 0.0:  # the knife edge: its sphere and the check that the cam is not thinner than it
        radii = old_curvature_radii(profile)
        assert r == 0.8 * float(radii[radii > 0.0].min())
        phis = np.linspace(0.0, 2.0 * math.pi, CHECKS, endpoint=False)
        assert nearest_distance(points_at(profile, phis), points_at(profile, phis, r)) == old_nearest(
            profile, r
        )
        assert tip_reason(contact) is None


def test_a_thin_cam_is_refused_with_the_same_distance() -> None:
    # test_cam_tip's cam with a waist 12 mm across, thinner than its 14 mm tip sphere
    phis = np.linspace(0.0, 2.0 * math.pi, 48, endpoint=False)
    thin = SplineProfile(tuple(0.006 + 0.044 * np.cos(phis) ** 2))
    contact = replace(scenarios.build("cam_knife_edge/spline").cams[0], profile=thin)
    reason = tip_reason(contact)
    assert reason is not None
    assert f"{old_nearest(thin, tip_radius(contact)):.4g} m from the offset" in reason


def test_the_mjcf_facets_are_the_per_piece_construction() -> None:
    scenario = scenarios.build("cam_knife_edge/spline")
    built = ADAPTER.build(scenario, ADAPTER.default_setting(scenario))
    contact = scenario.cams[0]
    radius, segments = old_facets(contact.profile, 512, tip_radius(contact))
    for k, (x1, y1, x2, y2) in enumerate(segments):
        assert f'fromto="{num(x1, y1, 0.0, x2, y2, 0.0)}"' in built.xml, k
    assert built.xml.count(f'size="{num(radius)}"') == 512
    assert mujoco.MjModel.from_xml_string(built.xml).npair == 512
