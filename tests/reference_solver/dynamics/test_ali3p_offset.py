"""A02's chain far from the origin: the compiled constraint rows sum positions apart from rotated
vectors (compiled.evaluate), so C's round-off is that of link-sized quantities whatever the
coordinates' size, and ALI3-P's round-off floor (compiled.ali3p_kernel) follows it. Before, on 40 m
coordinates, C lost their round-off to cancellation and the floor grew with them, so a slow
augmented Lagrangian next to a singular passage was taken for round-off: the rockers of the
reduced A02 moved 38 m along x stayed 3.4e-9 rad off the crank (7e-12 at the origin)."""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np

import scenarios
from reference_solver.compiled_system import CompiledSystem, constraint_system
from reference_solver.dynamics import simulate
from scenarios.bodies import GROUND, Point
from tests.support.a02_chain import FACTOR, a02_chain, a02_errors, moved_along_x

OFFSET = 38.0
"""Metres along x, as far as A02's 40-loop chain reaches."""
MOVED_CHAIN = 5.9e-12
"""The largest rocker-to-crank angle of the 2-loop A02 over 0.8 s in 8005 steps (the singular
instant 0.02 of a step from a step's end), moved OFFSET along x (measured: the same 5.9e-12 at 16
offsets in [32, 40); 3.4e-9 at every one before)."""
ROUND_OFF = 1.1e-16
"""The largest distance of the compiled C to C evaluated exactly at the same q (the same cos and
sin), the chain moved OFFSET along x, at 50 random states (measured; 6.5e-15 when positions and
rotated vectors were summed together)."""


def test_a_chain_far_from_the_origin_keeps_its_rockers_on_the_crank() -> None:
    scenario, grid, reduced = a02_chain(2, 0.8)
    analysis = simulate(
        moved_along_x(scenario, OFFSET), grid, method="ali3p", step=0.8 / 8005 * (1 + 1e-9), compiled=True
    )
    assert MOVED_CHAIN / FACTOR < a02_errors(analysis, reduced)[1] < FACTOR * MOVED_CHAIN


def _exact(scenario: scenarios.Scenario, system: CompiledSystem, q: np.ndarray) -> np.ndarray:
    """C of the revolute rows in rational arithmetic at q, with cos and sin as the kernel takes them."""
    layout = system.layout

    def point(p: Point) -> tuple[Fraction, Fraction]:
        if p.body == GROUND:
            return Fraction(p.local[0]), Fraction(p.local[1])
        k = layout.bodies.index(p.body)
        c, s = Fraction(math.cos(q[3 * k + 2])), Fraction(math.sin(q[3 * k + 2]))
        ux, uy = Fraction(p.local[0]), Fraction(p.local[1])
        return Fraction(q[3 * k]) + c * ux - s * uy, Fraction(q[3 * k + 1]) + s * ux + c * uy

    rows = []
    for joint in scenario.joints:
        (xi, yi), (xj, yj) = point(joint.p_i), point(joint.p_j)
        rows += [float(xi - xj), float(yi - yj)]
    return np.array(rows)


def test_the_compiled_rows_lose_nothing_to_the_coordinates_size() -> None:
    scenario = moved_along_x(scenarios.build("n_four_bar", overrides={"loops": 2}), OFFSET)
    system = constraint_system(scenario)
    assert isinstance(system, CompiledSystem)
    rng = np.random.default_rng(27)
    start = system.layout.initial_guess(scenario)
    worst = 0.0
    for _ in range(50):
        q = start + 1e-3 * rng.standard_normal(start.size)
        worst = max(worst, float(np.max(np.abs(system.evaluate(q, 0.0)[0] - _exact(scenario, system, q)))))
    assert ROUND_OFF / FACTOR < worst < FACTOR * ROUND_OFF, worst
