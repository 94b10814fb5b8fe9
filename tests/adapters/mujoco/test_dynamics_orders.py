"""Convergence of MuJoCo's integrators in free dynamics, error against the native truth over
three steps, and the correct digits of Andrews' squeezer at t = 0.03 s against the published
reference.

On the free four-bar the loop is a soft `connect` whose time constant is tc (four steps here), so it
shrinks with the step: with MuJoCo's own regulariser (these settings leave invweight0 as
compiled) the trajectory's error is then the regulariser's sag, about (1 - impedance) times the
unconstrained acceleration times tc^2, which falls as dt^2 and stays above RK4's own dt^4 (the
rule's default scales the regulariser away instead, adapters.mujoco.weights). So RK4 shows order 2
there, and its promised order 4 on the open-chain compound pendulum
(no constraint to soften). Euler, implicitfast and implicit are first order.
"""

from __future__ import annotations

import numpy as np
import pytest

import scenarios
from adapters.base import Setting
from scenarios.families.andrews_squeezer import ANGLES, REFERENCE, REFERENCE_T
from tests.support.mujoco.truths import ADAPTER, errors

FOUR_BAR = {"t_end": 0.25, "steps": 25}
PENDULUM = {"t_end": 1.0, "steps": 25}
BEST = Setting.of("RK4", dt=3e-6, tc=4.0 * 3e-6, impedance=0.9999)
"""The best of the default ladder on Andrews' squeezer."""


def order(name: str, mode: str, steps: tuple[float, ...], overrides: dict[str, float]) -> float:
    """The fitted slope of log position error against log step (the engine's step: the output
    grid never changes it)."""
    found = [
        errors(name, Setting.of(mode, dt=dt, tc=4.0 * dt, impedance=0.9999), **overrides)["position"]
        for dt in steps
    ]
    return float(np.polyfit(np.log(steps), np.log(found), 1)[0])


@pytest.mark.parametrize(
    ("name", "mode", "steps", "overrides", "expected"),
    [
        # measured 2.0e-6 / 1.8e-7 / 2.2e-8 m: slope 1.97
        ("four_bar_gravity", "RK4", (1e-3, 3e-4, 1e-4), FOUR_BAR, 2.0),
        # measured 5.0e-5 / 3.2e-6 / 2.0e-7: slope 3.99
        ("compound_pendulum", "RK4", (2e-2, 1e-2, 5e-3), PENDULUM, 4.0),
        # measured 3.2e-3 / 9.5e-4 / 3.2e-4: slope 1.01 (implicitfast the same to 1e-10: the
        # four-bar has no velocity-dependent force for it to treat implicitly)
        ("four_bar_gravity", "Euler", (1e-4, 3e-5, 1e-5), FOUR_BAR, 1.0),
        ("four_bar_gravity", "implicitfast", (1e-4, 3e-5, 1e-5), FOUR_BAR, 1.0),
        # measured 1.4e-3 / 3.9e-4 / 1.3e-4: slope 1.02
        ("four_bar_gravity", "implicit", (1e-4, 3e-5, 1e-5), FOUR_BAR, 1.0),
    ],
)
def test_convergence_order(
    name: str, mode: str, steps: tuple[float, ...], overrides: dict[str, float], expected: float
) -> None:
    assert order(name, mode, steps, overrides) == pytest.approx(expected, abs=0.4)


def andrews_digits(setting: Setting | None) -> np.ndarray:
    """Correct significant digits of the seven angles at t = 0.03 s against the published reference."""
    scenario = scenarios.load("andrews_squeezer")
    result = ADAPTER.run(scenario, setting)
    assert result.status == "ok", result.message
    assert result.trajectory is not None
    assert result.trajectory.times[-1] == pytest.approx(REFERENCE_T, abs=1e-15)
    angles = np.array([result.trajectory.extras[f"andrews.{a}"][-1] for a in ANGLES])
    return -np.log10(np.abs(angles - np.array(REFERENCE)) / np.abs(REFERENCE))  # type: ignore[no-any-return]


@pytest.mark.parametrize(
    ("setting", "measured"),
    [
        # the default, RK4 at the rule's step (measured before the regulariser was scaled: a floor)
        (None, (4.61, 4.52, 3.59, 4.58, 6.01, 4.58, 5.72)),
        # the ladder's best, RK4 at its finest step 3e-6 s
        (BEST, (7.86, 7.76, 6.64, 7.77, 8.41, 7.77, 8.89)),
        pytest.param(
            Setting.of("RK4", dt=1e-6, tc=4.0 * 1e-6, impedance=0.9999),
            (8.82, 8.72, 7.6, 8.73, 9.35, 8.73, 9.83),
            marks=pytest.mark.slow,
        ),
    ],
)
def test_andrews_squeezer_digits_at_0_03_s(setting: Setting | None, measured: tuple[float, ...]) -> None:
    digits = andrews_digits(setting)
    assert np.all(digits > np.array(measured) - 0.3), dict(zip(ANGLES, digits.round(2), strict=True))
