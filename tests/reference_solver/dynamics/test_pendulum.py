"""The physical pendulum (one uniform rod on a ground pivot) against its closed forms: the
small-oscillation law theta0 cos(w t), w = sqrt(3 g / (2 l)), and at a large amplitude the exact
elliptic-function solution theta = 2 arcsin(k sn(K - w t | k^2)), k = sin(theta0 / 2)."""

from __future__ import annotations

import math

import numpy as np
from scipy.special import ellipj, ellipk

import scenarios
from reference_solver.dynamics import simulate

G, L = 9.81, 0.5


def hanging_angle(name: str, **overrides: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Times, the rod's angle from the downward vertical and its rate."""
    analysis = simulate(scenarios.build(name, overrides=overrides))
    return analysis.times, analysis.q[:, 2] + math.pi / 2, analysis.qd[:, 2]


def test_small_oscillations_follow_the_harmonic_closed_form() -> None:
    times, theta, _ = hanging_angle("compound_pendulum/small_oscillation", t_end=1.0, steps=50)
    w = math.sqrt(3 * G / (2 * L))
    amplitude = 1e-4
    # The harmonic law is exact to O(theta0^3): a relative 1e-6 separates the two.
    np.testing.assert_allclose(theta, amplitude * np.cos(w * times), rtol=0, atol=1e-6 * amplitude)


def test_a_large_swing_follows_the_exact_elliptic_solution() -> None:
    theta0 = 2.0
    times, theta, omega = hanging_angle("compound_pendulum", links=1, theta0=theta0, t_end=1.0, steps=40)
    w = math.sqrt(3 * G / (2 * L))
    k = math.sin(theta0 / 2)
    sn, cn, _, _ = ellipj(ellipk(k * k) - w * times, k * k)
    np.testing.assert_allclose(theta, 2 * np.arcsin(k * sn), rtol=0, atol=1e-10)
    # theta_dot = -2 k w cn dn / sqrt(1 - k^2 sn^2) = -2 k w cn, since dn^2 = 1 - k^2 sn^2.
    np.testing.assert_allclose(omega, -2 * k * w * cn, rtol=0, atol=1e-9)
