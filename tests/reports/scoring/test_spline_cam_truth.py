"""The spline cams' truth (the refined native solve) against a second construction: the follower's
position, velocity and acceleration from the spline's own exact derivatives, in a few lines here.

The profile is rebuilt independently: the eccentric disc's radius d(phi) = e cos phi +
sqrt(R^2 - e^2 sin^2 phi) tabulated at the knots, a periodic cubic spline through it (scipy), its
derivatives d', d'', d''' exact (the spline's own). In the cam's frame the follower's axis points
along e(psi), psi = pi/2 - theta (psi' = -omega), and the follower's height y is measured along it.
- knife edge: y = d(psi), y' = d'(psi) psi', y'' = d''(psi) psi'^2;
- flat face: u'(phi).e(psi) = 0 (root finder), y = u.e; y' = u.e_perp psi', and phi' from the
  contact condition differentiated;
- roller: the roller centre y e(psi) = u(phi) + r n(phi) (root finder on its component across the
  axis); velocity and acceleration from w.u' = 0, w.w = r^2 (w = y e - u) differentiated once and
  twice (chain rule), each a 2x2 linear system in (phi', y') and (phi'', y'').
with u(phi) = d(phi) e(phi) and its derivatives by Leibniz' rule.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.interpolate import CubicSpline
from scipy.optimize import brentq

import scenarios
from reports.scoring.truth import NATIVE_REFINED, independent_truth
from reports.stress.truth import stress_truth
from scenarios.cam_profiles import EccentricDisc, SplineProfile
from scenarios.scenario import Scenario
from tests.support.measured import measured_table


def e(angle: float, turn: int = 0) -> np.ndarray:
    """The unit vector at `angle`, differentiated `turn` times (a quarter turn each)."""
    return np.array([math.cos(angle + turn * math.pi / 2), math.sin(angle + turn * math.pi / 2)])


class Profile:
    """The disc's radii at `knots` angles, through a periodic cubic spline."""

    def __init__(self, radius: float, eccentricity: float, knots: int) -> None:
        phis = np.linspace(0.0, 2 * math.pi, knots + 1)
        radii = eccentricity * np.cos(phis) + np.sqrt(radius**2 - (eccentricity * np.sin(phis)) ** 2)
        radii[-1] = radii[0]
        self.table = radii[:-1]
        self.spline = CubicSpline(phis, radii, bc_type="periodic")

    def u(self, phi: float) -> list[np.ndarray]:
        """u, u', u'', u''' at phi: sum over j of C(k, j) d^(j) e^(k - j)."""
        at = phi % (2 * math.pi)
        d = [float(self.spline(at, nu)) for nu in range(4)]
        return [sum(math.comb(k, j) * d[j] * e(phi, k - j) for j in range(k + 1)) for k in range(4)]  # type: ignore[misc]


def knife(p: Profile, psi: float, rate: float) -> tuple[float, float, float]:
    d = [float(p.spline(psi % (2 * math.pi), nu)) for nu in range(3)]
    return d[0], d[1] * rate, d[2] * rate**2


def flat(p: Profile, psi: float, rate: float) -> tuple[float, float, float]:
    along, across = e(psi), e(psi, 1)
    phi = brentq(lambda f: float(p.u(f)[1] @ along), psi - 0.5, psi + 0.5, xtol=1e-15, rtol=1e-15)
    u, u1, u2, _ = p.u(phi)
    phi_rate = -(u1 @ across) * rate / (u2 @ along)
    return (
        float(u @ along),
        float(u @ across) * rate,
        float((u1 @ across * phi_rate - u @ along * rate) * rate),
    )


def roller(p: Profile, psi: float, rate: float, r: float) -> tuple[float, float, float]:
    along, across = e(psi), e(psi, 1)

    def centre(phi: float) -> np.ndarray:
        u, u1 = p.u(phi)[:2]
        return u + r * np.array([u1[1], -u1[0]]) / np.hypot(*u1)  # the outward normal, r out

    phi = brentq(lambda f: float(centre(f) @ across), psi - 0.5, psi + 0.5, xtol=1e-15, rtol=1e-15)
    y = float(centre(phi) @ along)
    u, u1, u2, u3 = p.u(phi)
    w = y * along - u
    matrix = np.array([[w @ u2 - u1 @ u1, along @ u1], [-(w @ u1), w @ along]])
    phi_rate, y_rate = np.linalg.solve(matrix, [-y * rate * (across @ u1), -y * rate * (w @ across)])
    w_rate = y_rate * along + y * rate * across - u1 * phi_rate
    rest = 2 * y_rate * rate * across - y * rate**2 * along - u2 * phi_rate**2  # w'' without phi'', y''
    rhs = [
        -(rest @ u1 + 2 * (w_rate @ u2) * phi_rate + (w @ u3) * phi_rate**2),
        -(w_rate @ w_rate + w @ rest),
    ]
    return y, float(y_rate), float(np.linalg.solve(matrix, rhs)[1])


def follower(scenario: Scenario, times: np.ndarray) -> np.ndarray:
    """(N, 3): the follower's y, vy, ay from the second construction."""
    value = {k: v for k, v in scenario.parameters}
    big_r, ecc, omega, theta0 = (float(value[k]) for k in ("radius", "eccentricity", "omega", "theta0"))  # type: ignore[arg-type]
    profile = Profile(big_r, ecc, int(value["knots"]))  # type: ignore[arg-type]
    assert np.allclose(
        profile.table, SplineProfile.sample(EccentricDisc(big_r, ecc), len(profile.table)).table, 0, 1e-16
    )
    rows = []
    for t in times:
        psi = math.pi / 2 - (theta0 + omega * t)
        if scenario.family == "cam_knife_edge":
            rows.append(knife(profile, psi, -omega))
        elif scenario.family == "cam_flat_face":
            rows.append(flat(profile, psi, -omega))
        else:
            rows.append(roller(profile, psi, -omega, float(value["roller_radius"])))  # type: ignore[arg-type]
    return np.array(rows)


def harness_truth(name: str) -> tuple[Scenario, np.ndarray, np.ndarray]:
    """The scenario, its grid and the follower's (y, vy, ay) from the truth the harness uses."""
    scenario = scenarios.build(name)
    times = np.asarray(scenario.times())
    if "stress" in name:
        truth = stress_truth(scenario, times)
    else:
        named = independent_truth(scenario, times)
        assert named.name == NATIVE_REFINED
        truth = named.trajectory
    k = truth.bodies.index("follower")
    levels = [truth.level(level)[:, k, 1] for level in ("position", "velocity", "acceleration")]  # type: ignore[index]
    return scenario, times, np.column_stack(levels)


ERRORS = measured_table("spline_cam_truth")
"""name: the largest error of the harness's truth against the second construction, dimensionless
(y over R, vy over R omega, ay over R omega^2), measured: round-off at every level."""


@pytest.mark.parametrize("name", ERRORS)
def test_the_spline_cam_truth_meets_the_second_construction(name: str) -> None:
    """The native truth (refined, as the default suite uses it; the stress suite's for the 6-knot
    cams) within 3x its measured round-off of the spline's own derivatives, at every grid time."""
    scenario, times, truth = harness_truth(name)
    expected = follower(scenario, times)
    omega = abs(float(scenario.parameter("omega")))
    scale = float(scenario.parameter("radius")) * omega ** np.arange(3)
    errors = np.max(np.abs(truth - expected), axis=0) / scale
    print(name, "y, vy, ay errors:", errors)
    for level, (value, measured) in enumerate(zip(errors, ERRORS[name], strict=True)):
        assert value <= 3 * measured, (level, value)
