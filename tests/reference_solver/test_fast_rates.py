"""fast.rates' Newton on the dependent coordinates, seen through its iteration budget: from the
anchor (the last accepted step), a move dq of the independent coordinates leaves the tangent
predictor O(dq^2) off the constraint manifold; Newton squares that error at each step, the chord
(the anchor's LU of C_D) only multiplies it by O(dq). At dq = 1e-4 of the four-bar's and the
slider-crank's independent coordinates: with the predictor and Newton, 1e-8 then round-off, so
the second evaluation converges; with the chord, 1e-8, 1e-12, round-off: the third; without the
predictor, 1e-4, 1e-8, round-off: the third. Each count is required exactly (it converges within
it and not within one fewer), so a predictor, chord or stopping rule that works less well is seen
even where the answer, Newton's, is the same."""

from __future__ import annotations

import numpy as np
import pytest

from tests.reference_solver.dynamics.test_compiled_rates import both


def fewest_iterations(name: str, move: float, chord: int, predictor: int) -> int:
    """The smallest iteration limit under which the kernel's positions converge at the start's
    independent coordinates moved by `move`, from the anchor at the start."""
    compiled, plain, start = both(name)
    k = compiled.kernels
    y = plain.pack(start, np.zeros(3))
    compiled.anchor(start.t, y)
    moved = y[: plain.size] + move
    sizes = compiled.index[k.SIZES]
    for limit in range(1, 13):
        sizes[k.S_NEWTON], sizes[k.S_CHORD], sizes[k.S_HAS_FACTORS] = limit, chord, predictor
        status, _ = k.partitioned(k.POSITIONS, start.t, moved.copy(), compiled.nothing, *compiled.arguments)
        if status == k.OK:
            np.testing.assert_array_equal(compiled.vec[k.Q, plain.independent], moved)
            q, _ = plain.positions(start.t, moved)
            np.testing.assert_allclose(compiled.vec[k.Q, : q.size], q, rtol=0, atol=1e-13)
            return limit
        assert status == k.NOT_CONVERGED
    raise AssertionError("no convergence in 12 iterations")


@pytest.mark.parametrize("name", ["four_bar_gravity", "slider_crank_spring"])
def test_the_predictor_leaves_newton_one_step_and_the_chord_two(name: str) -> None:
    assert fewest_iterations(name, 1e-4, chord=0, predictor=1) == 2
    assert fewest_iterations(name, 1e-4, chord=1, predictor=1) == 3
    assert fewest_iterations(name, 1e-4, chord=0, predictor=0) == 3
