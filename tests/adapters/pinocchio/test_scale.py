"""Pinocchio's kinematic mode across mechanism scales: the Newton tolerance is in each row's own
units (lengths relative to the characteristic length), so the slider-crank scaled to a 1e-4 m and a
1e3 m crank is solved as accurately as the nominal one (measured: 1.6e-15 relative at both, 1.7e-15
nominal; before, the absolute tolerance left 6.2e-12 at 1e-4 m)."""

from __future__ import annotations

import numpy as np
import pytest

import scenarios
from adapters.pinocchio import PinocchioAdapter
from scenarios.closed_form import exact

SHORT = {"revolutions": 0.25, "steps": 20}


def relative_error(variant: str) -> float:
    scenario = scenarios.build("slider_crank", variant, overrides=SHORT)
    result = PinocchioAdapter().run(scenario)
    assert result.status == "ok", result.message
    assert result.trajectory is not None and result.trajectory.position is not None
    truth = exact(scenario, result.trajectory.times).select(result.trajectory.bodies)
    assert truth.position is not None
    diff = result.trajectory.position - truth.position
    lengths = np.hypot(diff[..., 0], diff[..., 1]).max() / scenario.characteristic_length
    return float(max(lengths, np.abs(diff[..., 2]).max()))


@pytest.mark.parametrize("variant", ["stress_scale_1e-4", "stress_scale_1e-2", "stress_scale_1e3"])
def test_a_scaled_mechanism_is_solved_as_accurately_as_the_nominal_one(variant: str) -> None:
    nominal = relative_error("default")
    assert nominal < 1e-14
    assert relative_error(variant) < max(4.0 * nominal, 1e-14)
