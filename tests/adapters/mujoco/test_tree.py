"""Which points of MuJoCo's body tree are affine in qpos (what lets a gear, a rack or a driver become
a linear equality): a point on a slide is its authored place plus the slide's coordinate along its
axis; a point under a hinge moves on a circle, so it is not affine, even at its own body's joint."""

from __future__ import annotations

import scenarios
from adapters.mujoco.tree import Affine, plan_tree, position
from scenarios.bodies import Point


def test_a_point_below_the_crank_s_hinge_is_not_affine_even_at_its_own_joint() -> None:
    scenario = scenarios.build("slider_crank")
    tree = plan_tree(scenario)
    assert [j.kind for j in tree.path("rod")] == ["hinge", "hinge"]
    own = tree.path("rod")[-1]
    assert position(tree, Point("rod", tuple(own.anchor))) is None
    assert position(tree, Point("rod", (0.0, 0.0))) is None


def test_a_point_on_the_slider_moves_with_the_slide_along_x() -> None:
    """The slider-crank's slider runs on the x axis: its points are x0 + s, y0 with s the slide."""
    scenario = scenarios.build("slider_crank")
    tree = plan_tree(scenario)
    found = position(tree, Point("slider", (0.1, 0.0)))
    assert found is not None
    x, y = found
    assert x.coefs == {"slide": 1.0} and y == Affine(0.0, {"slide": 0.0})
    x_at_centre = position(tree, Point("slider", (0.0, 0.0)))
    assert x_at_centre is not None and abs(x.const - x_at_centre[0].const - 0.1) < 1e-15
