"""The equivalent linkage of a disc cam is the same mechanism: the native solver on it reproduces the
cam's closed form; MuJoCo and Exudyn offer it under the same name, with the same default."""

from __future__ import annotations

import numpy as np
import pytest

from adapters.exudyn.adapter import ExudynAdapter
from adapters.mujoco.adapter import MujocoAdapter
from adapters.reference import ReferenceAdapter
from scenarios.cam_linkage import default_cam_model, equivalent_linkage, linkage_reason
from scenarios.closed_form import exact
from scenarios.registry import build


@pytest.mark.parametrize(
    "name", ["cam_knife_edge", "cam_roller", "cam_flat_face", "cam_knife_edge/stress_steep"]
)
def test_the_linkage_moves_the_follower_like_the_cam(name: str) -> None:
    scenario = build(name, overrides={"steps": 40})
    linkage = equivalent_linkage(scenario)
    assert not linkage.cams and linkage.output_bodies == scenario.output_bodies
    result = ReferenceAdapter().run(linkage)
    assert result.status == "ok" and result.trajectory is not None
    truth = exact(scenario, result.trajectory.times).select(scenario.output_bodies)
    got = result.trajectory.select(scenario.output_bodies)
    for level in ("position", "velocity", "acceleration"):
        scale = np.abs(truth.level(level)).max()
        assert np.abs(got.level(level) - truth.level(level)).max() < 1e-12 * max(scale, 1.0), level


def test_only_discs_have_a_linkage_and_both_engines_default_alike() -> None:
    spline = build("cam_roller/spline")
    assert linkage_reason(spline) and default_cam_model(spline) == "contact"
    for name in ("cam_roller", "cam_flat_face"):
        scenario = build(name)
        assert default_cam_model(scenario) == "linkage"
        assert MujocoAdapter().default_setting(scenario).get("cam_model") == "linkage"
    exudyn = ExudynAdapter()
    cam = build("cam_roller", overrides={"steps": 20})
    linkage = exudyn.run(cam)
    contact = exudyn.run(cam, exudyn.default_setting(cam).replace(cam_model="contact"))
    assert linkage.status == contact.status == "ok"
    assert linkage.trajectory is not None and contact.trajectory is not None
    assert np.allclose(linkage.trajectory.position, contact.trajectory.position, rtol=0, atol=1e-12)
