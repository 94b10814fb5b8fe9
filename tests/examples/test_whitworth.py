"""The Whitworth quick-return example against its closed form in polar coordinates about O4.

The block sits at A = O2 + r e(theta2) on a slot through O4; with s = |A - O4| and theta4 the
slot's angle, A's acceleration in the slot's rotating frame is
    A'' = (s'' - s theta4'^2) e_r + (s theta4'' + 2 s' theta4') e_t,
where 2 s' theta4' is the Coriolis term. Projecting the crank pin's known acceleration on e_r and
e_t gives s'' and theta4''. Nothing here is shared with the native solver.
"""

from __future__ import annotations

import numpy as np

from tests.support.examples.closed_forms import OMEGA, D, R, whitworth
from tests.support.examples.files import example, max_errors


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
