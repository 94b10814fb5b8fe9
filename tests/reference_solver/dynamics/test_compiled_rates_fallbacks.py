"""The compiled partitioned ODE's own logic (dynamics.compiled_rates) where the comparisons with the
plain path do not reach it: the fallback when a force law has no kernel, the retry of a Newton that
did not converge (C_D factored at every iteration, stalled accepted below RETRY_STALLED), the refusals
with their messages, and results that stay the caller's. The kernel is the real one throughout; the
retry is observed by a spy that records each call's Newton settings and passes it on unchanged."""

from __future__ import annotations

import dataclasses
import re

import numpy as np
import pytest

from reference_solver.compiled_system import constraint_system
from reference_solver.dynamics.compiled_rates import RETRY_STALLED, CompiledPartitioned, partitioned_ode
from reference_solver.dynamics.forward import initial_state
from reference_solver.dynamics.loads import Loads
from reference_solver.dynamics.mass import mass_diagonal
from reference_solver.dynamics.partition import (
    NEWTON_STEPS,
    STALLED,
    Partitioned,
    choose_independent,
)
from reference_solver.errors import ConvergenceError
from scenarios import GROUND, Body, Point, Revolute, Scenario, load
from scenarios.forces import AppliedTorque
from scenarios.motion_laws import Polynomial
from scenarios.motions import Harmonic, Motion
from tests.support.compiled_dynamics import both, random_states

Call = tuple[int, int, float, int, int]
"""(level, chord flag, stalled tolerance, Newton's iteration limit, status returned) of one kernel call."""


def spy(ode: CompiledPartitioned, fail_first: bool = False) -> list[Call]:
    """Record each call of the kernel with the Newton settings it ran under; with `fail_first`, the
    first call's status is reported as NOT_CONVERGED whatever the kernel returned (the retry is
    reached by no scene of the dynamics suite, so its protocol is tested by injecting the status)."""
    k, kernel = ode.kernels, ode.partitioned
    calls: list[Call] = []

    def recorded(level: int, t: float, y: np.ndarray, out: np.ndarray, *arguments: np.ndarray):  # type: ignore[no-untyped-def]
        sizes, tol = ode.index[k.SIZES], ode.vec[k.TOL]
        settings = (int(sizes[k.S_CHORD]), float(tol[1]), int(sizes[k.S_NEWTON]))
        status, residual = kernel(level, t, y, out, *arguments)
        if fail_first and not calls:
            status, residual = k.NOT_CONVERGED, 1.0
        calls.append((level, *settings, int(status)))
        return status, residual

    ode.partitioned = recorded
    return calls


def settled(ode: CompiledPartitioned) -> tuple[int, float]:
    k = ode.kernels
    return int(ode.index[k.SIZES, k.S_CHORD]), float(ode.vec[k.TOL, 1])


def with_torque(name: str, law: Motion) -> tuple[type, type]:
    """The ODE partitioned_ode gives for scenario `name` with a torque of `law` on its first body,
    over the compiled constraints, and the type it gives without the torque."""
    base = load(name)
    scenario = dataclasses.replace(
        base, forces=(*base.forces, AppliedTorque("drive", base.bodies[0].name, law))
    )
    kinds = []
    for s in (scenario, base):
        system = constraint_system(s)
        mass = mass_diagonal(s, system.layout)
        loads = Loads(s, system.layout, mass)
        start = initial_state(system, mass, loads, 0.0)
        kinds.append(
            type(partitioned_ode(system, mass, loads, start.q, choose_independent(system, start.jac)))
        )
    return kinds[0], kinds[1]


def test_a_force_law_without_a_kernel_keeps_the_plain_right_hand_side() -> None:
    assert with_torque("compound_pendulum", Polynomial((0.1, 0.2))) == (Partitioned, CompiledPartitioned)
    assert with_torque("compound_pendulum", Harmonic(0.1, 0.2, 3.0)) == (
        CompiledPartitioned,
        CompiledPartitioned,
    )


@pytest.mark.parametrize("call", ["rates", "state", "positions"])
def test_an_unconverged_newton_is_retried_without_the_chord_and_gives_the_plain_answer(call: str) -> None:
    """The kernel's first answer reported NOT_CONVERGED: the call is made once more with C_D factored
    at every iteration (chord 0) and stalled accepted below RETRY_STALLED, its answer is the plain
    path's, and the settings are restored for the next call."""
    compiled, plain, start = both("four_bar_gravity")
    k = compiled.kernels
    level = {"rates": k.RATES, "state": k.STATE, "positions": k.POSITIONS}[call]
    for t, y in random_states(plain, start, 3, seed=4):
        calls = spy(compiled, fail_first=True)
        if call == "positions":
            mine, theirs = compiled.positions(t, y[: plain.size]), plain.positions(t, y[: plain.size])
            pairs = list(zip(mine, theirs, strict=True))
        elif call == "state":
            a, b = compiled.state(t, y), plain.state(t, y)
            pairs = [(a.q, b.q), (a.qd, b.qd), (a.qdd, b.qdd), (a.lam, b.lam), (a.jac, b.jac)]
        else:
            pairs = [(compiled.rates(t, y), plain.rates(t, y))]
        assert calls == [
            (level, 1, STALLED, NEWTON_STEPS, k.NOT_CONVERGED),
            (level, 0, RETRY_STALLED, NEWTON_STEPS, k.OK),
        ]
        assert settled(compiled) == (1, STALLED)
        for mine_, theirs_ in pairs:
            scale = max(1.0, float(np.max(np.abs(theirs_))))
            np.testing.assert_allclose(mine_, theirs_, rtol=0, atol=1e-12 * scale)


def test_a_newton_that_fails_its_retry_too_is_refused_with_where_and_how_far() -> None:
    """One iteration allowed, from a state 0.2 rad off the anchor: both tries fail. The error names the
    scenario, the time and the last residual, and carries Newton's last iterate, whose independent
    coordinates are the state's."""
    compiled, plain, start = both("four_bar_gravity")
    k = compiled.kernels
    compiled.index[k.SIZES, k.S_NEWTON] = 1
    y = plain.pack(start, np.zeros(3))
    y[: plain.size] += 0.2
    calls = spy(compiled)
    with pytest.raises(ConvergenceError) as caught:
        compiled.rates(0.125, y)
    error = caught.value
    pattern = (
        r"four_bar_gravity: the dependent coordinates did not converge at t=0\.125 "
        r"\(constraint residual (\S+)\)"
    )
    match = re.fullmatch(pattern, str(error))
    assert match is not None, str(error)
    assert 1e-10 < float(match[1]) < 1.0 and error.time == 0.125
    assert error.q is not None and error.q.shape == start.q.shape
    np.testing.assert_array_equal(error.q[plain.independent], y[: plain.size])
    assert [c[1:] for c in calls] == [
        (1, STALLED, 1, k.NOT_CONVERGED),
        (0, RETRY_STALLED, 1, k.NOT_CONVERGED),
    ]
    assert settled(compiled) == (1, STALLED)


def test_a_reduced_mass_matrix_with_a_zero_pivot_is_refused_without_a_retry() -> None:
    compiled, plain, start = both("compound_pendulum")
    k = compiled.kernels
    compiled.vec[k.MASS] = 0.0
    calls = spy(compiled)
    y = plain.pack(start, np.zeros(3))
    with pytest.raises(np.linalg.LinAlgError, match=r"^the reduced mass matrix has an exactly zero pivot$"):
        compiled.rates(start.t, y)
    assert [c[-1] for c in calls] == [k.SINGULAR]


def test_positions_and_states_are_the_caller_s_not_views_of_the_kernel_s_arrays() -> None:
    compiled, plain, start = both("four_bar_gravity")
    (t0, y0), (t1, y1) = random_states(plain, start, 2, seed=8)
    q, jac = compiled.positions(t0, y0[: plain.size])
    s = compiled.state(t0, y0)
    kept = [a.copy() for a in (q, jac, s.q, s.qd, s.qdd, s.lam, s.jac, s.loads.generalized)]
    compiled.state(t1, y1)
    for before, now in zip(kept, (q, jac, s.q, s.qd, s.qdd, s.lam, s.jac, s.loads.generalized), strict=True):
        np.testing.assert_array_equal(now, before)


def test_each_right_hand_side_is_counted_once() -> None:
    compiled, plain, start = both("compound_pendulum")
    assert compiled.evaluations == 0
    for count, (t, y) in enumerate(random_states(plain, start, 3, seed=3), start=1):
        compiled.rates(t, y)
        assert compiled.evaluations == count
    compiled.state(start.t, plain.pack(start, np.zeros(3)))
    assert compiled.evaluations == 3  # a state is not a right-hand side


def test_more_independent_coordinates_than_rows_and_seven() -> None:
    """A rod pinned at its end to the ground, level and at rest, beside three free bodies: 12
    coordinates, 2 rows, 10 independent (more than the 7 entries of the kernel's size row). The free
    bodies fall with g; the rod turns with theta'' = -m g a / (J + m a^2), a = 0.5 from its pin, its
    centre with y'' = a theta'' and x'' = 0."""
    g, mass, inertia, a = 9.81, 2.0, 0.3, 0.5
    rod = Body("rod", (a, 0.0, 0.0), mass=mass, inertia=inertia)
    free = tuple(Body(f"free{k}", (1.0 + k, 1.0, 0.2 * k), mass=1.0 + k, inertia=0.1) for k in range(3))
    pin = Revolute("pin", Point(GROUND, (0.0, 0.0)), Point("rod", (-a, 0.0)))
    scenario = Scenario("rod_and_free", "default", (rod, *free), (pin,), (), 1.0, 1, 1.0, gravity=(0.0, -g))
    system = constraint_system(scenario)
    masses = mass_diagonal(scenario, system.layout)
    loads = Loads(scenario, system.layout, masses)
    start = initial_state(system, masses, loads, 0.0)
    ode = partitioned_ode(system, masses, loads, start.q, choose_independent(system, start.jac))
    assert isinstance(ode, CompiledPartitioned) and ode.size == 10
    turn = -mass * g * a / (inertia + mass * a * a)
    expected = np.array([0.0, a * turn, turn, *(0.0, -g, 0.0) * 3])
    state = ode.state(0.0, ode.pack(start, np.zeros(3)))
    np.testing.assert_allclose(state.qdd, expected, rtol=0, atol=1e-12)
