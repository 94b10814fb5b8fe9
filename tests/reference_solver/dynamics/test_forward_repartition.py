"""Forward dynamics (dynamics.forward) where the partitioned method repartitions, on a grid of one
time, and in the columns its result fills for the kinematic Analysis.

The released four-bar (four_bar_gravity, 0.25 s) keeps one partition at REPARTITION = 0.1 but, its
dependent block's conditioning falling as it swings, is partitioned anew 9 times at 0.95 (measured):
the event must fire where that conditioning reaches 0.95 of its value at the partition's start,
the motion must stay the one-partition motion to the integration's tolerance, and the counts must
be the partitions made and the right-hand sides evaluated in all of them."""

from __future__ import annotations

import functools
import itertools

import numpy as np
import pytest

from reference_solver.compiled_system import CompiledSystem
from reference_solver.dynamics import forward
from reference_solver.dynamics.forward import DynamicAnalysis, initial_state, simulate
from reference_solver.dynamics.loads import Loads
from reference_solver.dynamics.mass import mass_diagonal
from reference_solver.dynamics.partition import Partitioned
from reference_solver.system import ConstraintSystem
from tests.support.forward_scenes import FRACTION, RTOL, rod, swinging_four_bar


@functools.cache
def one_partition(driven: bool = False) -> DynamicAnalysis:
    """The four-bar at the module's REPARTITION (0.1): one partition all the way."""
    return simulate(swinging_four_bar(driven), rtol=RTOL)


@pytest.mark.parametrize("driven", [False, True], ids=["released", "with a harmonic torque"])
def test_a_repartition_happens_where_the_dependent_block_s_conditioning_fell_to_its_fraction(
    monkeypatch: pytest.MonkeyPatch, driven: bool
) -> None:
    reference = one_partition(driven)  # before the patches below
    assert reference.partitions == 1
    made: list[tuple[Partitioned, np.ndarray]] = []
    make = forward.partitioned_ode

    def recorded(system, mass, loads, q, independent):  # type: ignore[no-untyped-def]
        ode = make(system, mass, loads, q, independent)
        made.append((ode, q.copy()))
        return ode

    calls = []
    rates = Partitioned.rates

    def counted(self: Partitioned, t: float, y: np.ndarray) -> np.ndarray:
        calls.append(t)
        return rates(self, t, y)

    monkeypatch.setattr(forward, "partitioned_ode", recorded)
    monkeypatch.setattr(Partitioned, "rates", counted)
    monkeypatch.setattr(forward, "REPARTITION", FRACTION)
    scenario = swinging_four_bar(driven)
    result = simulate(scenario, rtol=RTOL)
    assert result.partitions == len(made) and len(made) >= 5  # measured 9
    assert result.evaluations == len(calls)
    # the same motion as with one partition, to the tolerance: measured 2.2e-9 apart in q (m and
    # rad, L = 0.05 m), 1.1e-7 in q' (of 38 rad/s); with the torque 2.5e-9 and 3.2e-8 (of 43 rad/s)
    np.testing.assert_allclose(result.q, reference.q, rtol=0, atol=7e-9)
    np.testing.assert_allclose(result.qd, reference.qd, rtol=0, atol=1e-8 * np.max(np.abs(reference.qd)))
    system = ConstraintSystem(scenario)  # no driver: C_q does not depend on time
    for (ode, start), (_, end) in itertools.pairwise(made):
        chosen = ode.conditioning(system.jacobian(start, 0.0))
        reached = ode.conditioning(system.jacobian(end, 0.0))
        assert reached == pytest.approx(FRACTION * chosen, rel=1e-13)  # measured 1.1e-15


def test_a_grid_of_one_time_is_the_initial_state() -> None:
    """The assembled state and its rates at t0, with every extra: nothing is integrated. The time
    given as an integer is a time in seconds all the same (a float grid)."""
    scenario = rod()
    result = simulate(scenario, times=[0])
    assert result.times.dtype == np.float64 and result.times.tolist() == [0.0]
    system = ConstraintSystem(scenario)
    mass = mass_diagonal(scenario, system.layout)
    start = initial_state(system, mass, Loads(scenario, system.layout, mass), 0.0)
    np.testing.assert_array_equal(result.q, [start.q])
    np.testing.assert_array_equal(result.qd, [start.qd])
    assert result.evaluations == 0 and result.partitions == 0
    assert result.extras["pin_1.fx"].shape == (1,) and result.extras["energy.balance"].tolist() == [0.0]


@pytest.mark.parametrize("method", ["DOP853", "ali3p"])
def test_the_analysis_columns_of_a_dynamic_result(method: str) -> None:
    """No kinematic Newton ran: 0 iterations (integers) and no condition estimate (NaN) at each
    output; the residual column is max |C(q_k)| / L, here C in metres over L = 0.5 m. ALI3-P makes
    no partition, the partitioned method one; both count their evaluations."""
    scenario = rod()
    result = simulate(scenario, times=np.linspace(0.0, 0.2, 5), method=method, step=1e-3)
    motion = result.motion
    assert motion.iterations.dtype.kind == "i" and motion.iterations.tolist() == [0] * 5
    assert motion.rcond.dtype == np.float64 and np.all(np.isnan(motion.rcond))
    system = ConstraintSystem(scenario)
    misses = [np.max(np.abs(system.residual(q, 0.0))) / 0.5 for q in result.q]
    np.testing.assert_array_equal(motion.residual, misses)
    assert result.partitions == (0 if method == "ali3p" else 1)
    # ALI3-P evaluates the constraints at least once in each of its 200 steps (measured 400: 2 each)
    assert result.evaluations >= (200 if method == "ali3p" else 1)


def test_the_four_bar_s_residual_column_is_relative_to_its_length() -> None:
    """The released four-bar's constraints miss by round-off (nonzero at some outputs): the column is
    that miss over the characteristic length, max |C(q_k)| / L, not times it."""
    result = one_partition()
    system = ConstraintSystem(swinging_four_bar())
    length = system.layout.length_scale
    misses = [np.max(np.abs(system.residual(q, 0.0))) / length for q in result.q]
    assert max(misses) > 0.0 and length != 1.0
    np.testing.assert_allclose(result.motion.residual, misses, rtol=1e-12, atol=0)


def test_newton_s_start_moves_with_the_integrator_s_accepted_steps(monkeypatch: pytest.MonkeyPatch) -> None:
    """The anchor is set while the integrator runs (after each step it accepts), between right-hand
    sides, not only on the walk through the outputs afterwards (partition.py: a rejected trial
    stage must leave nothing behind)."""
    events: list[str] = []
    anchor, rates = Partitioned.anchor, Partitioned.rates

    def anchoring(self: Partitioned, t: float, y: np.ndarray) -> None:
        events.append("anchor")
        anchor(self, t, y)

    def evaluating(self: Partitioned, t: float, y: np.ndarray) -> np.ndarray:
        events.append("rates")
        return rates(self, t, y)

    monkeypatch.setattr(Partitioned, "anchor", anchoring)
    monkeypatch.setattr(Partitioned, "rates", evaluating)
    for method in ("DOP853", "Radau"):
        events.clear()
        simulate(rod(), times=np.linspace(0.0, 0.2, 3), method=method)
        last = len(events) - 1 - events[::-1].index("rates")
        assert "anchor" in events[:last]


@pytest.mark.parametrize("compiled", [False, True])
def test_fast_asks_for_the_compiled_constraints(monkeypatch: pytest.MonkeyPatch, compiled: bool) -> None:
    """`compiled` evaluates the constraints on the compiled path (their values are the plain path's to
    1e-12, so only the system's kind tells the two apart)."""
    kinds: list[type] = []
    make = forward.partitioned_ode

    def recorded(system, mass, loads, q, independent):  # type: ignore[no-untyped-def]
        kinds.append(type(system))
        return make(system, mass, loads, q, independent)

    monkeypatch.setattr(forward, "partitioned_ode", recorded)
    simulate(rod(), times=np.linspace(0.0, 0.1, 2), compiled=compiled)
    assert kinds == [CompiledSystem if compiled else ConstraintSystem]
