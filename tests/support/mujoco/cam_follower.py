"""A MuJoCo cam follower's errors against the cam's closed form."""

from __future__ import annotations

import numpy as np

import scenarios
from adapters.base import Setting
from adapters.mujoco import MujocoAdapter
from adapters.reference import ReferenceAdapter

ADAPTER = MujocoAdapter()


def follower_errors(name: str, pieces: int) -> np.ndarray:
    """The follower's largest position, velocity and acceleration error against the native solver."""
    scenario = scenarios.build(name)
    truth = ReferenceAdapter().run(scenario).trajectory
    setting: Setting = ADAPTER.default_setting(scenario).replace(cam_pieces=pieces)
    result = ADAPTER.run(scenario, setting)
    assert result.status == "ok", result.message
    assert result.trajectory is not None and truth is not None
    got, want = result.trajectory.select(("follower",)), truth.select(("follower",))
    pairs = [
        (got.position, want.position),
        (got.velocity, want.velocity),
        (got.acceleration, want.acceleration),
    ]
    return np.array([np.abs(np.asarray(a)[..., 1] - np.asarray(b)[..., 1]).max() for a, b in pairs])
