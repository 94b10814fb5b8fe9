"""The spur gear pair's bodies as built: uniform discs of unit areal density (m = pi r^2,
J = m r^2 / 2 about the centre) whose guessed poses sit on their pivots, the output gear's at the
centre distance (r_in + r_out external, r_out - r_in internal). The kinematic closed form cannot see
the masses, and assembly would move a misplaced guess onto its pivot; the dynamics use them as built."""

from __future__ import annotations

import math

import pytest

import scenarios


@pytest.mark.parametrize(("variant", "distance"), [("", 0.05 + 0.15), ("/internal", 0.15 - 0.05)])
def test_the_gears_are_uniform_discs_on_their_pivots(variant: str, distance: float) -> None:
    scenario = scenarios.build("spur_gears" + variant)
    bodies = {body.name: body for body in scenario.bodies}
    for name, radius, centre in (("gear_in", 0.05, 0.0), ("gear_out", 0.15, distance)):
        body = bodies[name]
        mass = math.pi * radius**2
        assert body.mass == pytest.approx(mass, rel=1e-15)
        assert body.inertia == pytest.approx(mass * radius**2 / 2, rel=1e-15)
        assert body.guess[:2] == pytest.approx((centre, 0.0), abs=1e-15)
