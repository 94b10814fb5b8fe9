"""examples/damped_oscillators.toml against the closed form of two damped linear oscillators.

The block (with the disc it carries) and the disc each obey m u'' + c u' + k u = 0 about their
equilibria (shifted by the constant load / stiffness), released from rest:
    u(t) = e^(-s t) (u0 cos(wd t) + (s u0 / wd) sin(wd t)),  u'(t) = -e^(-s t) (wn^2 / wd) u0 sin(wd t)
with wn = sqrt(k / m), s = c / (2 m), wd = sqrt(wn^2 - s^2), and u'' = -wn^2 u - 2 s u'.
Nothing here is shared with the native solver.
"""

from __future__ import annotations

import numpy as np

from tests.support.examples.closed_forms import BLOCK, DISC, oscillator
from tests.support.examples.closed_forms import damped_oscillators as expected
from tests.support.examples.files import example, max_errors


def test_damped_oscillators_against_closed_form() -> None:
    scenario = example("damped_oscillators")
    errors = max_errors(scenario, expected(np.asarray(scenario.times())))
    # Scales: 0.1 m and 0.4 rad amplitudes at 10 rad/s; the native default is DOP853 at rtol 1e-12.
    # Measured: 1.5e-12 (m, rad), 6.8e-12 (per s), 1.4e-10 (per s^2).
    assert errors["position"] < 1e-10, errors
    assert errors["velocity"] < 1e-9, errors
    assert errors["acceleration"] < 1e-8, errors


def test_the_loads_matter() -> None:
    """The closed form moves: each load shifts its equilibrium, and the damping decays the swing."""
    t = np.linspace(0.0, 2.0, 201)
    x, theta = oscillator(t, BLOCK)[0], oscillator(t, DISC)[0]
    assert abs(x[-1] - 0.31) < 0.02 and abs(theta[-1] - 0.1) < 0.1
    assert np.ptp(x) > 0.1 and np.ptp(theta) > 0.5
