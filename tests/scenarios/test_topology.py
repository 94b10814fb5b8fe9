"""The engine-neutral spanning tree: trees, single and double loops, gears on a carrier."""

from __future__ import annotations

import pytest

import scenarios
from scenarios import GROUND, Body, Point, Revolute, Scenario
from scenarios.topology import TopologyError, spanning_tree
from tests.support.mechanisms import differential_train


def _parents(name: str) -> dict[str, tuple[str, str]]:
    tree = spanning_tree(scenarios.build(name))
    return {e.child: (e.parent, e.joint.name) for e in tree.edges}


def test_a_slider_crank_closes_its_loop_at_a_pin_not_at_the_slide() -> None:
    tree = spanning_tree(scenarios.build("slider_crank"))
    # the slide first (prismatic before revolute), then the pins in the scenario's order
    assert [e.joint.name for e in tree.edges] == ["slide", "O", "A"]
    assert tree.closures == ("B",)


def test_a_four_bar_leaves_one_pin_to_close_the_loop() -> None:
    tree = spanning_tree(scenarios.build("four_bar"))
    assert len(tree.edges) == 3
    assert len(tree.closures) == 1
    children = [e.child for e in tree.edges]
    for edge in tree.edges:  # every parent is placed before its child
        assert edge.parent == GROUND or children.index(edge.parent) < children.index(edge.child)


def test_a_chain_of_two_loops_leaves_two_closures() -> None:
    tree = spanning_tree(scenarios.build("four_bar_chain", overrides={"loops": 2}))
    assert len(tree.edges) == 5 and len(tree.closures) == 2


def test_gears_on_a_carrier_close_loops_and_the_planet_hangs_from_the_arm() -> None:
    bodies, joints = differential_train(0.06, 0.03)
    scenario = Scenario("differential", "default", bodies, joints, (), 1.0, 10, 0.1)
    tree = spanning_tree(scenario)
    assert tree.edge_of("planet").parent == "arm"
    assert "mesh" in tree.closures


def test_an_unreachable_body_is_named() -> None:
    loose = Scenario(
        "loose",
        "default",
        (Body("a", (0.0, 0.0, 0.0)), Body("b", (1.0, 0.0, 0.0))),
        (Revolute("pin", Point(GROUND), Point("a")),),
        (),
        1.0,
        10,
        1.0,
    )
    with pytest.raises(TopologyError, match="bodies b are not reached from the ground"):
        spanning_tree(loose)
