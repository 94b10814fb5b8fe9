"""MuJoCo's kinematic mode (Newton on MuJoCo's own rows) reaches round-off on every scenario of the
kinematic catalogue but the spline cams (the cams as their equivalent linkage, the default cam
model), against the closed forms."""

from __future__ import annotations

import numpy as np
import pytest

from adapters.base import Setting
from adapters.mujoco.adapter import MujocoAdapter
from scenarios.closed_form import exact
from scenarios.registry import build
from tests.support.mujoco.scenes import DISC_SCENARIOS


@pytest.mark.parametrize("name", DISC_SCENARIOS)
def test_kinematic_mode_is_exact_at_every_level(name: str) -> None:
    scenario = build(name, overrides={"steps": 50})
    result = MujocoAdapter().run(scenario, Setting.of("kinematic"))
    assert result.status == "ok", result.message
    assert result.measures.startswith("adapter loop")
    assert result.trajectory is not None
    truth = exact(scenario, result.trajectory.times).select(scenario.output_bodies)
    got = result.trajectory.select(scenario.output_bodies)
    omega = abs(float(scenario.parameter("omega")))
    length = scenario.characteristic_length
    for level, rate in (("position", 1.0), ("velocity", omega), ("acceleration", omega**2)):
        diff = np.abs(got.level(level) - truth.level(level))
        assert diff[..., :2].max() / (length * rate) < 1e-12, level
        assert diff[..., 2].max() / rate < 1e-12, level


def test_kinematic_mode_refuses_cam_contacts_with_the_reason() -> None:
    result = MujocoAdapter().run(build("cam_roller"), Setting.of("kinematic", cam_model="contact"))
    assert result.status == "unsupported"
    assert "contact" in result.message
