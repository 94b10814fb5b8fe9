"""Every cam profile's d(phi) and its first three derivatives, and every motion law's f(t) and its
first two, against central differences of the level below, at many random points. A new profile or
law is covered by adding an instance of it to PROFILES or LAWS; the coverage test fails until one is
there for every member of scenarios' Profile and Motion unions."""

from __future__ import annotations

import math
import typing
from collections.abc import Callable

import numpy as np
import pytest

from scenarios.cam_profiles import EccentricDisc, LobedProfile, Profile, SplineProfile
from scenarios.motion_laws import Polynomial, TabulatedLaw
from scenarios.motions import Constant, ConstantSpeed, Harmonic, Motion

POINTS = 200
STEP = 1e-5
"""Central differences of step h: truncation h^2/6 times the next derivative, round-off eps/h."""

PROFILES: dict[str, Profile] = {
    "disc": EccentricDisc(radius=0.05, eccentricity=0.01),
    "disc_near_limit": EccentricDisc(radius=0.05, eccentricity=0.045),
    "lobed_3": LobedProfile(radius=0.05, amplitude=0.005, lobes=3),
    "lobed_7": LobedProfile(radius=0.04, amplitude=0.002, lobes=7),
    "spline_24": SplineProfile.sample(EccentricDisc(radius=0.05, eccentricity=0.01), 24),
    "spline_lobed": SplineProfile(
        tuple(0.05 + 0.004 * math.cos(3 * 2 * math.pi * k / 40) for k in range(40))
    ),
}

LAWS: dict[str, Motion] = {
    "constant_speed": ConstantSpeed(start=0.3, rate=-7.0),
    "harmonic": Harmonic(mean=0.1, amplitude=0.4, omega=9.0, phase=0.7),
    "constant": Constant(value=1.2),
    "polynomial": Polynomial((0.2, -1.0, 3.0, 0.5, -0.25)),
    "tabulated_clamped": TabulatedLaw(
        times=(0.0, 0.1, 0.25, 0.4, 0.5), values=(0.0, 0.2, 0.1, 0.6, 0.5), ends="clamped", slopes=(0.5, -1.0)
    ),
    "tabulated_periodic": TabulatedLaw(
        times=(0.0, 0.2, 0.5, 0.7, 1.0), values=(0.0, 0.3, -0.2, 0.1, 0.0), ends="periodic"
    ),
}


def _kinks(item: object) -> np.ndarray:
    """Where a derivative of `item` may jump (a spline's knots, a clamped table's ends)."""
    if isinstance(item, SplineProfile):
        return np.linspace(-2 * math.pi, 4 * math.pi, 3 * len(item.table) + 1)
    if isinstance(item, TabulatedLaw):
        period = item.times[-1] - item.times[0]
        return np.concatenate([np.asarray(item.times) + k * period for k in range(-3, 4)])
    return np.empty(0)


def _points(rng: np.random.Generator, low: float, high: float, kinks: np.ndarray) -> np.ndarray:
    """Random points in [low, high] at least 3 steps from every kink."""
    points = rng.uniform(low, high, 4 * POINTS)
    if kinks.size:
        near = np.min(np.abs(points[:, None] - kinks[None, :]), axis=1) < 3 * STEP
        points = points[~near]
    return points[:POINTS]


def _check(levels: Callable[[float], tuple[float, ...]], points: np.ndarray) -> None:
    """Each level k >= 1 against the central difference of level k - 1, to 1e-7 of that level's
    largest magnitude over the points (no smaller than the level below's over the step, scaled)."""
    values = np.array([levels(float(x)) for x in points])
    above = np.array([levels(float(x) + STEP) for x in points])
    below = np.array([levels(float(x) - STEP) for x in points])
    for k in range(1, values.shape[1]):
        difference = (above[:, k - 1] - below[:, k - 1]) / (2 * STEP)
        scale = max(float(np.max(np.abs(values[:, k]))), float(np.max(np.abs(values[:, k - 1]))), 1e-300)
        worst = float(np.max(np.abs(difference - values[:, k])))
        assert worst <= 1e-7 * scale, (
            f"derivative {k}: finite differences differ by {worst:.3e} (scale {scale:.3e})"
        )


@pytest.mark.parametrize("name", PROFILES)
def test_a_profile_s_three_derivatives_match_finite_differences(name: str) -> None:
    profile = PROFILES[name]
    rng = np.random.default_rng(sum(map(ord, name)))
    _check(profile.radii, _points(rng, -2 * math.pi, 4 * math.pi, _kinks(profile)))


@pytest.mark.parametrize("name", LAWS)
def test_a_motion_law_s_two_derivatives_match_finite_differences(name: str) -> None:
    law = LAWS[name]
    rng = np.random.default_rng(sum(map(ord, name)))
    _check(lambda t: (law.f(t), law.df(t), law.ddf(t)), _points(rng, -0.5, 1.5, _kinks(law)))


@pytest.mark.parametrize(("union", "instances"), [(Profile, PROFILES), (Motion, LAWS)])
def test_every_profile_and_law_of_the_vocabulary_is_checked(union: object, instances: dict) -> None:
    kinds = set(typing.get_args(union))
    assert kinds == {type(item) for item in instances.values()}
