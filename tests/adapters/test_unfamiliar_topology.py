"""Every engine builds a mechanism unlike any family from a scenario file alone: the trammel of
Archimedes, two sliders in perpendicular ground slots (one along y) joined by a rod whose absolute
angle is driven, with no ground pivot anywhere. The adapters know no family, so each either builds
it and agrees with the closed form, or says `unsupported` and why.

Closed form, rod angle phi = phi0 + w t, the rod's frame at slider A, slider B at its far end (l, 0):
    A = (-l cos phi, 0),   B = (0, l sin phi)
    A' = (l w sin phi, 0), B' = (0, l w cos phi);  A'' = (l w^2 cos phi, 0), B'' = (0, -l w^2 sin phi)
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import adapters
from reports.scoring.level_error import LEVEL_COLUMNS, level_errors
from scenarios import ConstantSpeed, Scenario, Trajectory
from scenarios.files import read_scenario
from tests.support.bounds import held

LENGTH, OMEGA, PHI0 = 0.3, 5.0, 0.3
TRAMMEL = Path(__file__).with_name("trammel.toml")
"""The scenario file; it states LENGTH, OMEGA and PHI0 (checked below)."""
MEASURED: dict[str, tuple[float, float, float]] = {
    "reference": (0.0, 1.5e-16, 2.4e-16),
    "pinocchio": (1.9e-16, 3.0e-16, 3.6e-16),
    "mujoco": (1.5e-11, 3.6e-11, 1.5e-10),  # soft closures, the regulariser scaled (adapters.mujoco.weights)
    "exudyn": (1.8e-15, 8.3e-7, 1.7e-6),  # GA3 after its run-in (7.6e-3 without: the start-up transient)
}
"""Dimensionless (position, velocity, acceleration) errors at each engine's default setting,
measured, held two-sided (tests.support.bounds)."""


def closed_form(scenario: Scenario) -> Trajectory:
    t = np.asarray(scenario.times())
    phi = PHI0 + OMEGA * t
    c, s, z = np.cos(phi), np.sin(phi), np.zeros_like(t)
    r, w = LENGTH, OMEGA
    a = [np.column_stack(v) for v in ((-r * c, z, z), (r * w * s, z, z), (r * w * w * c, z, z))]
    b = [np.column_stack(v) for v in ((z, r * s, z), (z, r * w * c, z), (z, -r * w * w * s, z))]
    rod = [
        np.column_stack(v)
        for v in ((-r * c, z, phi), (r * w * s, z, np.full_like(t, w)), (r * w * w * c, z, z))
    ]
    levels = [np.stack([a[k], b[k], rod[k]], axis=1) for k in range(3)]
    return Trajectory(t, ("slider_a", "slider_b", "rod"), *levels)


@pytest.mark.parametrize("engine", list(MEASURED))
def test_engine_builds_the_trammel(engine: str) -> None:
    adapter = adapters.load(engine)  # the engines are hard dependencies: a missing one fails here
    scenario = read_scenario(TRAMMEL)
    assert scenario.characteristic_length == LENGTH and scenario.t_end == 2 * math.pi / OMEGA
    assert scenario.drivers[0].motion == ConstantSpeed(PHI0, OMEGA)  # type: ignore[union-attr]
    reason = adapter.supports(scenario)
    if reason is not None:
        pytest.fail(f"{engine} does not build the trammel: {reason}")
    result = adapter.run(scenario, adapter.default_setting(scenario), np.asarray(scenario.times()))
    assert result.status == "ok" and result.trajectory is not None, result.message
    found = level_errors(scenario, result.trajectory, closed_form(scenario))
    held([found[column] for column in LEVEL_COLUMNS.values()], MEASURED[engine])
