"""compiled.rates' Newton on the dependent coordinates, seen through its iteration budget: from the
anchor (the last accepted step), a move dq of the independent coordinates leaves the tangent
predictor O(dq^2) off the constraint manifold; Newton squares that error at each step, the chord
(the anchor's LU of C_D) only multiplies it by O(dq). At dq = 1e-4 of the four-bar's and the
slider-crank's independent coordinates: with the predictor and Newton, 1e-8 then round-off, so
the second evaluation converges; with the chord, 1e-8, 1e-12, round-off: the third; without the
predictor, 1e-4, 1e-8, round-off: the third. Each count is required exactly (it converges within
it and not within one fewer), so a predictor, chord or stopping rule that works less well is seen
even where the answer, Newton's, is the same. And the kernel on driven chains (the catalogue's
dynamic scenes have no driver): C_t, the predictor's time terms and the drivers' power."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pytest

import scenarios
from reference_solver.compiled_system import constraint_system
from reference_solver.dynamics.compiled_rates import CompiledPartitioned, partitioned_ode
from reference_solver.dynamics.forward import initial_state
from reference_solver.dynamics.loads import Loads
from reference_solver.dynamics.mass import mass_diagonal
from scenarios import Scenario
from tests.support.compiled_dynamics import both, compiled_and_plain
from tests.support.partitioned_scenes import driven_chain, rocked_chain


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


@pytest.mark.parametrize("build", [driven_chain, rocked_chain])
def test_a_driven_chain_s_rates_and_driver_power_are_the_plain_path_s(build: Callable[[], Scenario]) -> None:
    """The catalogue's dynamic scenes have no driver, so neither C_t nor the drivers' power: a chain
    whose first link is driven at constant speed, or rocked harmonically under a harmonic torque,
    from the anchor at the start (the predictor on), at random states up to 0.05 s later."""
    compiled, plain, start = compiled_and_plain(build())
    y0 = plain.pack(start, np.zeros(3))
    compiled.anchor(start.t, y0)
    plain.anchor(start.t, y0)
    rng = np.random.default_rng(12)
    for _ in range(6):
        t = float(rng.uniform(0.0, 0.05))
        y = y0 + np.concatenate(
            [1e-3 * rng.uniform(-1, 1, plain.size), rng.uniform(-1, 1, plain.size), [0, 0, 0]]
        )
        mine, theirs = compiled.rates(t, y), plain.rates(t, y)
        assert abs(theirs[-1]) > 1e-3  # the drivers do work
        np.testing.assert_allclose(mine, theirs, rtol=0, atol=1e-12 * max(1.0, float(np.max(np.abs(theirs)))))


def fewest_from_anchor(
    compiled: CompiledPartitioned, y0: np.ndarray, moved: np.ndarray, chord: int, predictor: int
) -> int:
    """fewest_iterations for an ODE built here: anchored at (0, y0), positions at `moved`."""
    k = compiled.kernels
    compiled.anchor(0.0, y0)
    sizes = compiled.index[k.SIZES]
    for limit in range(1, 13):
        sizes[k.S_NEWTON], sizes[k.S_CHORD], sizes[k.S_HAS_FACTORS] = limit, chord, predictor
        status, _ = k.partitioned(k.POSITIONS, 0.0, moved.copy(), compiled.nothing, *compiled.arguments)
        if status == k.OK:
            return limit
    raise AssertionError("no convergence in 12 iterations")


def test_the_predictor_moves_every_independent_coordinate_and_cancels_a_steady_c_t() -> None:
    """Two independent coordinates (the first link's x and the second link's angle of a free
    two-link chain), moved by (1e-4, -2e-4): the same counts as above. The chain driven at constant
    speed, at the anchor's time: C_t(t) - C_t(anchor) = 0, so the predictor leaves Newton one step."""
    chain = scenarios.build("compound_pendulum", overrides={"links": 2, "theta0": 0.3})
    system = constraint_system(chain)
    mass = mass_diagonal(chain, system.layout)
    loads = Loads(chain, system.layout, mass)
    start = initial_state(system, mass, loads, 0.0)
    compiled = partitioned_ode(system, mass, loads, start.q, np.array([0, 5]))
    assert isinstance(compiled, CompiledPartitioned)
    y0 = compiled.pack(start, np.zeros(3))
    moved = y0[:2] + np.array([1e-4, -2e-4])
    counts = [fewest_from_anchor(compiled, y0, moved, c, p) for c, p in ((0, 1), (1, 1), (0, 0))]
    assert counts == [2, 3, 3]
    driven, plain, start = compiled_and_plain(driven_chain())
    y0 = plain.pack(start, np.zeros(3))
    assert fewest_from_anchor(driven, y0, y0[: plain.size] + 1e-4, chord=0, predictor=1) == 2
