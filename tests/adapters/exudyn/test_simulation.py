"""The Exudyn reader's outputs between its steps: a motion cubic in time, sampled on the steps with
its exact velocity and acceleration, is read back exactly at an output between two steps (cubic
Hermite in position and velocity, linear in acceleration, each exact for a cubic), with a warning
that counts the interpolated outputs and estimates their cost (nothing, for a cubic)."""

from __future__ import annotations

import numpy as np
import pytest

from adapters.exudyn.assembly import States
from adapters.exudyn.simulation import _on_grid

H = 0.1


def _motion(t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """q = 1 + 2 t - t^2 + t^3 / 2 in one coordinate, 3 t in another, with q' and q''."""
    q = np.stack([1 + 2 * t - t**2 + 0.5 * t**3, 3 * t], axis=1)
    v = np.stack([2 - 2 * t + 1.5 * t**2, np.full_like(t, 3.0)], axis=1)
    a = np.stack([-2 + 3 * t, np.zeros_like(t)], axis=1)
    return q, v, a


def test_an_output_between_steps_of_a_cubic_motion_is_read_exactly_with_a_warning() -> None:
    steps = np.arange(4) * H
    lattice = States(*_motion(steps))
    times = np.array([0.0, 0.05, 0.2, 0.27])
    with pytest.warns(UserWarning) as caught:
        states = _on_grid(lattice, times, H, np.ones(2))
    q, v, a = _motion(times)
    assert np.abs(states.q - q).max() < 1e-14
    assert np.abs(states.v - v).max() < 1e-14
    assert np.abs(states.a - a).max() < 1e-14
    message = str(caught[0].message)
    assert message.startswith("Exudyn: 2 of 4 output times fall between its steps (an uneven grid)")
    cost = float(message.split("interpolation error is about ")[1].split(" ")[0])
    assert cost < 1e-12  # the cubic Hermite and the quintic agree on a cubic, to round-off


def test_outputs_on_the_steps_are_the_steps_states_without_a_warning() -> None:
    steps = np.arange(4) * H
    lattice = States(*_motion(steps))
    with np.errstate(all="raise"):
        states = _on_grid(lattice, steps[[0, 2, 3]], H, np.ones(2))
    assert (states.q == lattice.q[[0, 2, 3]]).all() and (states.a == lattice.a[[0, 2, 3]]).all()
