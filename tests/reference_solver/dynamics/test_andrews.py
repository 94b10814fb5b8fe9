"""Andrews' squeezing mechanism against the Test Set for IVP Solvers: its consistent initial
accelerations, its own equations integrated independently, and its published reference solution
at t = 0.03 s (about ten correct digits is what the reference itself carries)."""

from __future__ import annotations

import numpy as np
import pytest

import scenarios
from reference_solver.dynamics import simulate
from scenarios.families.andrews_squeezer import ANGLES, INITIAL_ACCELERATIONS, REFERENCE, REFERENCE_T
from tests.support.andrews_equations import angles_at


def angles(t_end: float, steps: int = 1, compiled: bool = False) -> np.ndarray:
    """The test set's seven angles at t_end, on the plain or the compiled path (`compiled`)."""
    scenario = scenarios.build("andrews_squeezer", overrides={"t_end": t_end, "steps": steps})
    extras = simulate(scenario, compiled=compiled).extras
    return np.array([extras[f"andrews.{a}"][-1] for a in ANGLES])


def correct_digits(value: np.ndarray, reference: np.ndarray) -> np.ndarray:
    return -np.log10(np.abs(value - reference) / np.abs(reference))  # type: ignore[no-any-return]


def test_initial_accelerations_are_the_test_sets() -> None:
    analysis = simulate(scenarios.build("andrews_squeezer", overrides={"t_end": 1e-6, "steps": 1}))
    k1, k2 = analysis.layout.body_column("k1"), analysis.layout.body_column("k2")
    assert k1 is not None and k2 is not None
    beta_dd = analysis.qdd[0, k1 + 2]
    theta_dd = analysis.qdd[0, k2 + 2] - beta_dd
    assert beta_dd == pytest.approx(INITIAL_ACCELERATIONS[0], rel=1e-12)
    assert theta_dd == pytest.approx(INITIAL_ACCELERATIONS[1], rel=1e-12)


@pytest.mark.parametrize("compiled", [False, True], ids=["plain", "compiled"])
def test_the_absolute_coordinate_model_matches_the_test_sets_equations_early_on(compiled: bool) -> None:
    np.testing.assert_allclose(angles(0.003, compiled=compiled), angles_at(0.003), rtol=0, atol=1e-11)


@pytest.mark.slow
@pytest.mark.parametrize("compiled", [False, True], ids=["plain", "compiled"])
def test_the_published_reference_at_0_03_s(compiled: bool) -> None:
    ours = angles(REFERENCE_T, compiled=compiled)
    digits = correct_digits(ours, np.array(REFERENCE))
    # Measured: 10.1 10.0 9.6 10.4 11.9 10.4 12.5 (gamma, the smallest angle, has an absolute error
    # of 1e-11); the test set's own equations integrated at rtol 1e-13 give the same digits, so the
    # reference, not the model, limits them. The compiled path: the same digits to 0.1.
    assert np.all(digits > 9.5), dict(zip(ANGLES, digits.round(2), strict=True))
    np.testing.assert_allclose(ours, angles_at(REFERENCE_T), rtol=0, atol=1e-10)
