"""What the Exudyn dynamics tests share: the native truth (reference_solver.dynamics, independent of
Exudyn), the dimensionless position error against it, and the energy T + V of a trajectory."""

from __future__ import annotations

from functools import cache

import numpy as np

import scenarios
from adapters.base import Setting
from adapters.exudyn import ExudynAdapter
from reference_solver.dynamics import simulate
from reports.scoring.level_error import level_errors
from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory
from tests.support.truths import compiled

ADAPTER = ExudynAdapter()


@cache
def scenario(name: str, **overrides: float) -> Scenario:
    return scenarios.build(name, overrides=overrides) if overrides else scenarios.load(name)


@cache
def truth(s: Scenario, rtol: float = 1e-12) -> Trajectory:
    """The native truth on the scenario's grid (cached: the tests only read it)."""
    return simulate(s, s.times(), rtol=rtol, compiled=compiled(s)).trajectory()


def run(s: Scenario, setting: Setting | None = None) -> Trajectory:
    result = ADAPTER.run(s, setting)
    assert result.status == "ok", result.message
    assert result.trajectory is not None
    return result.trajectory


def position_error(s: Scenario, mine: Trajectory, ref: Trajectory) -> float:
    """The harness's dimensionless position-level error (lengths over L, angles in rad)."""
    return level_errors(s, mine, ref, ("position",))["error_position"]


def energy(s: Scenario, t: Trajectory) -> np.ndarray:
    """T + V at each grid time: 1/2 m v^2 + 1/2 J w^2 - m g.r summed over the bodies."""
    assert t.position is not None and t.velocity is not None
    g = np.asarray(s.gravity, dtype=float)
    total = np.zeros(len(t.times))
    for k, name in enumerate(t.bodies):
        body = s.body(name)
        v, r = t.velocity[:, k], t.position[:, k]
        total += 0.5 * body.mass * (v[:, 0] ** 2 + v[:, 1] ** 2) + 0.5 * body.inertia * v[:, 2] ** 2
        total -= body.mass * (r[:, :2] @ g)
    return total


def potential_range(s: Scenario, t: Trajectory) -> float:
    """The range of the gravity potential over the run: the energy the motion exchanges."""
    assert t.position is not None
    g = np.asarray(s.gravity, dtype=float)
    v = sum(-s.body(b).mass * (t.position[:, k, :2] @ g) for k, b in enumerate(t.bodies))
    return float(np.ptp(v))
