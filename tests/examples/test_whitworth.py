"""The Whitworth quick-return example against its closed form in polar coordinates about O4.

The block sits at A = O2 + r e(theta2) on a slot through O4; with s = |A - O4| and theta4 the
slot's angle, A's acceleration in the slot's rotating frame is
    A'' = (s'' - s theta4'^2) e_r + (s theta4'' + 2 s' theta4') e_t,
where 2 s' theta4' is the Coriolis term. Projecting the crank pin's known acceleration on e_r and
e_t gives s'' and theta4''. Nothing here is shared with the native solver.
"""

from __future__ import annotations

import numpy as np

from tests.examples.support import example, max_errors

R, D, OMEGA = 0.1, 0.05, 10.0


def whitworth(t: np.ndarray) -> dict[str, tuple[np.ndarray, np.ndarray, np.ndarray]]:
    theta2 = OMEGA * t
    c2, s2 = np.cos(theta2), np.sin(theta2)
    a = np.column_stack([R * c2, D + R * s2])  # O4 at the origin
    da = np.column_stack([-R * OMEGA * s2, R * OMEGA * c2])
    dda = np.column_stack([-R * OMEGA**2 * c2, -R * OMEGA**2 * s2])
    s = np.hypot(a[:, 0], a[:, 1])
    theta4 = np.unwrap(np.arctan2(a[:, 1], a[:, 0]))
    e_r = np.column_stack([np.cos(theta4), np.sin(theta4)])
    e_t = np.column_stack([-e_r[:, 1], e_r[:, 0]])
    ds = np.einsum("ij,ij->i", da, e_r)
    omega4 = np.einsum("ij,ij->i", da, e_t) / s
    coriolis = 2.0 * ds * omega4
    alpha4 = (np.einsum("ij,ij->i", dda, e_t) - coriolis) / s
    n = t.size
    zeros, full = np.zeros(n), np.full(n, OMEGA)
    pivot = np.column_stack([zeros, np.full(n, D)])
    return {
        "crank": (np.column_stack([pivot, theta2]), np.column_stack([zeros, zeros, full]), np.zeros((n, 3))),
        "block": (
            np.column_stack([a, theta4]),
            np.column_stack([da, omega4]),
            np.column_stack([dda, alpha4]),
        ),
        "slotted_link": (
            np.column_stack([zeros, zeros, theta4]),
            np.column_stack([zeros, zeros, omega4]),
            np.column_stack([zeros, zeros, alpha4]),
        ),
    }


def test_whitworth_against_closed_form() -> None:
    scenario = example("whitworth_quick_return")
    errors = max_errors(scenario, whitworth(np.asarray(scenario.times())))
    # Scales: r = 0.1 m, the slot turns at up to 20 rad/s and 135 rad/s^2.
    assert errors["position"] < 1e-13
    assert errors["velocity"] < 1e-12
    assert errors["acceleration"] < 1e-10


def test_coriolis_term_matters() -> None:
    """Without the Coriolis term the slot's angular acceleration would be wrong by up to 2 s' w4 / s:
    the example is a real test of it."""
    t = np.asarray(example("whitworth_quick_return").times())
    alpha4 = whitworth(t)["slotted_link"][2][:, 2]
    assert np.max(np.abs(alpha4)) > 100.0


def test_quick_return_ratio() -> None:
    """The slot turns half a turn (the working stroke, A above O4's horizontal) while the crank turns
    pi + 2 asin(d / r), the other half while it turns pi - 2 asin(d / r): a 2:1 ratio for d = r / 2."""
    t = np.linspace(0.0, 2 * np.pi / OMEGA, 20001)
    theta4 = whitworth(t)["slotted_link"][0][:, 2]
    above = np.mean(np.sin(theta4) > 0.0)
    expected = (np.pi + 2 * np.arcsin(D / R)) / (2 * np.pi)
    assert abs(above - expected) < 1e-3
