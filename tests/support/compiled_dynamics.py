"""The compiled partitioned dynamics beside the plain one: both right-hand sides of a scenario and
random states to compare them on."""

from __future__ import annotations

import numpy as np

from reference_solver.compiled_system import constraint_system
from reference_solver.dynamics.compiled_rates import CompiledPartitioned, partitioned_ode
from reference_solver.dynamics.forward import initial_state
from reference_solver.dynamics.loads import Loads
from reference_solver.dynamics.mass import mass_diagonal
from reference_solver.dynamics.partition import Partitioned, State, choose_independent
from scenarios import Scenario, load


def both(name: str) -> tuple[CompiledPartitioned, Partitioned, State]:
    """The compiled and the plain ODE of one scenario, on the same partition, and its start."""
    scenario = load(name)
    return compiled_and_plain(scenario, float(scenario.times()[0]))


def random_states(ode: Partitioned, start: State, count: int, seed: int) -> list[tuple[float, np.ndarray]]:
    """(t, y) near the start: independent positions moved by up to 1e-3 of their scale, rates and
    work integrals random of the start's rates' size."""
    rng = np.random.default_rng(seed)
    y0 = ode.pack(start, np.zeros(3))
    k = ode.size
    speed = max(1.0, float(np.max(np.abs(start.qd))))
    cols = ode.system.column_scales[ode.independent]
    states = []
    for _ in range(count):
        y = y0.copy()
        y[:k] += 1e-3 * cols * rng.uniform(-1, 1, k)
        y[k:] = speed * rng.uniform(-1, 1, y.size - k)
        states.append((start.t + float(rng.uniform(0, 1e-3)), y))
    return states


def compiled_and_plain(scenario: Scenario, t0: float = 0.0) -> tuple[CompiledPartitioned, Partitioned, State]:
    """The compiled and the plain ODE of `scenario` on the same partition, and its start at `t0`."""
    compiled_system, plain = constraint_system(scenario), constraint_system(scenario, compiled=False)
    mass = mass_diagonal(scenario, plain.layout)
    start = initial_state(plain, mass, Loads(scenario, plain.layout, mass), t0)
    independent = choose_independent(plain, start.jac)
    compiled = partitioned_ode(
        compiled_system, mass, Loads(scenario, compiled_system.layout, mass), start.q, independent
    )
    assert isinstance(compiled, CompiledPartitioned)
    return (
        compiled,
        Partitioned(plain, mass, Loads(scenario, plain.layout, mass), start.q, independent),
        start,
    )
