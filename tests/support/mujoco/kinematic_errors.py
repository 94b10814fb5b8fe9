"""MuJoCo's kinematic errors against the closed forms: positions, and velocities and accelerations
relative to the driver's rate."""

from __future__ import annotations

import numpy as np

import scenarios
from adapters.base import Setting
from adapters.mujoco import MujocoAdapter
from scenarios.closed_form import exact

ADAPTER = MujocoAdapter()


def errors(name: str, setting: Setting | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Position errors (lengths, angles) and relative velocity and acceleration errors."""
    scenario = scenarios.build(name)
    result = ADAPTER.run(scenario, setting)
    assert result.status == "ok", result.message
    trajectory = result.trajectory
    assert trajectory is not None
    truth = exact(scenario, trajectory.times).select(trajectory.bodies)
    out = []
    omega = abs(float(scenario.parameter("omega")))
    for level in ("position", "velocity", "acceleration"):
        got, want = trajectory.level(level), truth.level(level)
        assert got is not None and want is not None
        error = np.abs(got - want)
        if level == "position":
            out += [error[..., :2].max(), error[..., 2].max()]
            continue
        # Relative to the level's size; accelerations at least omega |v| (zero at constant speed).
        size = np.abs(want).max()
        if level == "acceleration":
            size = max(size, omega * np.abs(truth.velocity).max())
        out.append(error.max() / size)
    return np.array(out[:2]), np.array(out[2:])
