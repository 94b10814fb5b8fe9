"""The compiled right-hand side of the partitioned method (dynamics.compiled_rates, compiled.rates)
against the plain one (dynamics.partition with the plain constraints) to 1e-12 on random states
near each scenario's start, and its rates against finite differences of its own positions: q' is
the derivative of the positions along (q'_I, t), q'' the derivative of q' along (q''_I, t)."""

from __future__ import annotations

import numpy as np
import pytest

from reference_solver.compiled_system import constraint_system
from reference_solver.dynamics import simulate
from reference_solver.dynamics.compiled_rates import partitioned_ode
from reference_solver.dynamics.forward import initial_state
from reference_solver.dynamics.loads import Loads
from reference_solver.dynamics.mass import mass_diagonal
from reference_solver.dynamics.partition import Partitioned, State, choose_independent
from scenarios import load
from tests.support.compiled_dynamics import both, random_states

DYNAMIC = [
    "slider_crank_spring",
    "four_bar_gravity",
    "andrews_squeezer",
    "compound_pendulum",
    "n_four_bar",
    "stiff_spring",
]


def close(mine: np.ndarray, theirs: np.ndarray, what: str) -> None:
    scale = max(1.0, float(np.max(np.abs(theirs))))
    np.testing.assert_allclose(mine, theirs, rtol=0, atol=1e-12 * scale, err_msg=what)


@pytest.mark.parametrize("name", DYNAMIC)
def test_compiled_right_hand_side_is_the_plain_one_on_random_states(name: str) -> None:
    compiled, plain, start = both(name)
    for t, y in random_states(plain, start, 20, seed=5):
        close(compiled.rates(t, y), plain.rates(t, y), "rates")
        mine, theirs = compiled.state(t, y), plain.state(t, y)
        for field in ("q", "qd", "qdd", "lam", "jac"):
            close(getattr(mine, field), getattr(theirs, field), field)
        close(mine.loads.generalized, theirs.loads.generalized, "Q_e")
        wanted = (theirs.loads.potential, theirs.loads.applied_power, theirs.loads.dissipation)
        close(
            np.array([mine.loads.potential, mine.loads.applied_power, mine.loads.dissipation]),
            np.array(wanted),
            "energies",
        )


def along(ode: Partitioned, s: State, y: np.ndarray, dt: float) -> State:
    """The state a time dt from s along its own rates: q_I + dt q'_I, q'_I + dt q''_I."""
    ind = ode.independent
    moved = np.concatenate([s.q[ind] + dt * s.qd[ind], s.qd[ind] + dt * s.qdd[ind], y[2 * ode.size :]])
    return ode.state(s.t + dt, moved)


@pytest.mark.parametrize("name", DYNAMIC)
def test_compiled_rates_are_the_derivatives_of_the_compiled_positions(name: str) -> None:
    """Central differences, step 1e-6 of time: q' and q'' to 1e-7 of their largest entry."""
    compiled, _, start = both(name)
    h = 1e-6
    for t, y in random_states(compiled, start, 5, seed=9):
        s = compiled.state(t, y)
        ahead, behind = along(compiled, s, y, h), along(compiled, s, y, -h)
        compiled.state(t, y)  # Newton back near the centre for the next state
        for derivative, value in (
            ((ahead.q - behind.q) / (2 * h), s.qd),
            ((ahead.qd - behind.qd) / (2 * h), s.qdd),
        ):
            bound = 1e-7 * max(1.0, float(np.max(np.abs(value))))
            np.testing.assert_allclose(derivative, value, rtol=0, atol=bound)


def test_the_plain_constraints_keep_the_plain_right_hand_side() -> None:
    scenario = load("four_bar_gravity")
    system = constraint_system(scenario, compiled=False)
    mass = mass_diagonal(scenario, system.layout)
    loads = Loads(scenario, system.layout, mass)
    start = initial_state(system, mass, loads, float(scenario.times()[0]))
    ode = partitioned_ode(system, mass, loads, start.q, choose_independent(system, start.jac))
    assert type(ode) is Partitioned


@pytest.mark.parametrize("name", DYNAMIC)
def test_compiled_conditioning_is_the_plain_one(name: str) -> None:
    """The eigenvalues of B^T B against the plain path's singular values of B, to 1e-10."""
    compiled, plain, start = both(name)
    for t, y in random_states(plain, start, 10, seed=2):
        jac = plain.state(t, y).jac
        assert compiled.conditioning(jac) == pytest.approx(plain.conditioning(jac), rel=1e-10)


def test_radau_integrates_the_same_motion_on_both_paths() -> None:
    """Radau differentiates the right-hand side numerically (columns of a matrix: non-contiguous
    states); measured 6.2e-15 apart in q, 1.8e-11 in q'' (of 1.4e3: 1.3e-14), over 0.1 s at rtol
    1e-10: round-off (Newton's iterates differ within its tolerance), bounded at three times that."""
    scenario = load("slider_crank_spring", {"t_end": 0.1, "steps": 10})
    compiled = simulate(scenario, rtol=1e-10, method="Radau", compiled=True)
    plain = simulate(scenario, rtol=1e-10, method="Radau")
    assert np.max(np.abs(compiled.q - plain.q)) < 2e-14
    assert np.max(np.abs(compiled.qdd - plain.qdd)) < 4e-14 * np.max(np.abs(plain.qdd))
