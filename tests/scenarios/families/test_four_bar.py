"""The four-bar's bodies and joints as built: links of unit linear density (m = length,
J = m l^2 / 12) with the coupler's mass and inertia times `mass_ratio`, and the four pivots named as
the family describes them (crank O2-A, coupler A-B, rocker O4-B): a joint's name names its reaction
force in every engine's output. The kinematic closed form sees neither."""

from __future__ import annotations

import pytest

import scenarios


@pytest.mark.parametrize("ratio", [1.0, 3.0])
def test_the_links_are_uniform_rods_and_the_coupler_carries_the_mass_ratio(ratio: float) -> None:
    scenario = scenarios.build("four_bar", overrides={"mass_ratio": ratio})
    lengths = {name: float(scenario.parameter(f"{name}_length")) for name in ("crank", "coupler", "rocker")}
    for name, length in lengths.items():
        body = scenario.body(name)
        factor = ratio if name == "coupler" else 1.0
        assert body.mass == pytest.approx(factor * length, rel=1e-15)
        assert body.inertia == pytest.approx(factor * length**3 / 12, rel=1e-15)


def test_the_pivots_are_named_o2_a_b_o4_at_the_links_ends() -> None:
    scenario = scenarios.build("four_bar")
    p = {
        name: float(scenario.parameter(f"{name}_length")) for name in ("ground", "crank", "coupler", "rocker")
    }
    joints = {joint.name: joint for joint in scenario.joints}
    assert sorted(joints) == ["A", "B", "O2", "O4"]
    ends = {
        "O2": (("ground", (0.0, 0.0)), ("crank", (-p["crank"] / 2, 0.0))),
        "A": (("crank", (p["crank"] / 2, 0.0)), ("coupler", (-p["coupler"] / 2, 0.0))),
        "B": (("coupler", (p["coupler"] / 2, 0.0)), ("rocker", (p["rocker"] / 2, 0.0))),
        "O4": (("ground", (p["ground"], 0.0)), ("rocker", (-p["rocker"] / 2, 0.0))),
    }
    for name, (first, second) in ends.items():
        found = [(point.body, tuple(point.local)) for point in (joints[name].p_i, joints[name].p_j)]
        assert found == [first, second], name
