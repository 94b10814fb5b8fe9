"""The cost of the partitioned right-hand side itself, without the integrator around it: the calls
one DOP853 integration makes (its states and the steps it accepts, recorded on the compiled path
over the first partition) replayed through the plain and the compiled right-hand side in turns.

benchmarks.dynamics_speed divides the whole integration by its right-hand sides, which charges
scipy's own step (its stage sums, error norm and dense output, about as long as the compiled
kernel on the smallest scenes) to the right-hand side; this measures the call `ode.rates(t, y)`
alone, with the anchor moved where the integration moved it, so each Newton starts where it did.
"""

from __future__ import annotations

import time
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from unittest import mock

import numpy as np

from reference_solver.compiled_system import constraint_system
from reference_solver.dynamics import simulate
from reference_solver.dynamics.compiled_rates import CompiledPartitioned, partitioned_ode
from reference_solver.dynamics.forward import initial_state
from reference_solver.dynamics.loads import Loads
from reference_solver.dynamics.mass import mass_diagonal
from reference_solver.dynamics.partition import Partitioned, choose_independent
from scenarios.scenario import Scenario

Call = tuple[bool, float, np.ndarray]
"""(True for a right-hand side, False for an accepted step's anchor, t, y)."""


@contextmanager
def _recording(calls: list[Call]) -> Iterator[None]:
    """Record the compiled ODE's right-hand sides and anchors, from its first instance only."""
    rates, anchor = CompiledPartitioned.rates, CompiledPartitioned.anchor
    first: list[int] = []

    def keep(ode: CompiledPartitioned, kind: bool, t: float, y: np.ndarray) -> None:
        if not first:
            first.append(id(ode))
        if id(ode) == first[0]:
            calls.append((kind, float(t), np.array(y, dtype=float)))

    def recorded_rates(ode: CompiledPartitioned, t: float, y: np.ndarray) -> np.ndarray:
        keep(ode, True, t, y)
        return rates(ode, t, y)

    def recorded_anchor(ode: CompiledPartitioned, t: float, y: np.ndarray) -> None:
        keep(ode, False, t, y)
        anchor(ode, t, y)

    with (
        mock.patch.object(CompiledPartitioned, "rates", recorded_rates),
        mock.patch.object(CompiledPartitioned, "anchor", recorded_anchor),
    ):
        yield


def _odes(scenario: Scenario) -> tuple[Partitioned, Partitioned]:
    """The plain and the compiled ODE at the scenario's start, on the partition simulate chooses."""
    plain, compiled = constraint_system(scenario, compiled=False), constraint_system(scenario)
    mass = mass_diagonal(scenario, plain.layout)
    start = initial_state(compiled, mass, Loads(scenario, compiled.layout, mass), float(scenario.times()[0]))
    independent = choose_independent(compiled, start.jac)  # as simulate(compiled=True) chose it
    return (
        Partitioned(plain, mass, Loads(scenario, plain.layout, mass), start.q, independent),
        partitioned_ode(compiled, mass, Loads(scenario, compiled.layout, mass), start.q, independent),
    )


def _replay(ode: Partitioned, calls: list[Call]) -> float:
    """CPU seconds spent in the right-hand-side calls of `calls` (anchors made, not timed)."""
    spent = 0.0
    for is_rates, t, y in calls:
        if not is_rates:
            ode.anchor(t, y)
            continue
        begin = time.process_time()
        ode.rates(t, y)
        spent += time.process_time() - begin
    return spent


def rhs_seconds(
    scenario: Scenario, grid: Sequence[float], repeats: int, limit: int = 1000
) -> tuple[float, float]:
    """Seconds per right-hand-side call, plain and compiled (the best of `repeats`, in turns), over
    the first `limit` calls of the compiled integration's first partition."""
    calls: list[Call] = []
    with _recording(calls):
        simulate(scenario, grid, compiled=True)
    calls = calls[:limit]
    count = sum(kind for kind, _, _ in calls)
    best = [np.inf, np.inf]
    for _ in range(repeats):
        for side, ode in enumerate(_odes(scenario)):
            best[side] = min(best[side], _replay(ode, calls) / count)
    return best[0], best[1]
