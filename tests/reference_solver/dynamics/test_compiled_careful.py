"""The compiled ALI3-P step's two additions for singular passages (dynamics.compiled_ali3p,
compiled.ali3p_kernel's P_CAREFUL): a careful step (Newton and the projections through the Schur
complement from the first iteration) reaches the same state as the augmented Lagrangian where that
converges, and a step of another length is the plain step at that length."""

from __future__ import annotations

import numpy as np

import scenarios
from reference_solver.compiled_system import constraint_system
from reference_solver.dynamics.ali3p import Ali3p, StepState
from reference_solver.dynamics.compiled_ali3p import CompiledAli3p, ali3p_stepper
from reference_solver.dynamics.forward import initial_state
from reference_solver.dynamics.loads import Loads
from reference_solver.dynamics.mass import mass_diagonal


def _start(compiled: bool, h: float) -> tuple[Ali3p, StepState]:
    scenario = scenarios.build("n_four_bar", overrides={"loops": 3, "t_end": 0.1, "steps": 2})
    system = constraint_system(scenario, compiled=compiled)
    mass = mass_diagonal(scenario, system.layout)
    loads = Loads(scenario, system.layout, mass)
    start = initial_state(system, mass, loads, 0.0)
    return ali3p_stepper(system, mass, loads, h), StepState(
        start.t, start.q, start.qd, start.qdd, start.lam.copy(), start.jac
    )


def test_careful_steps_reach_the_augmented_lagrangian_s_state() -> None:
    """30 steps of 1e-3 on a 3-loop chain, far from its singular position: the same positions to
    1e-11 of the length and rates to 1e-11 of it per half step (measured: 1e-15 and 3e-14); one
    Schur factorization per careful step, none otherwise."""
    h, count = 1e-3, 30
    normal, s = _start(True, h)
    careful, _ = _start(True, h)
    assert isinstance(normal, CompiledAli3p) and isinstance(careful, CompiledAli3p)
    careful.careful = True
    assert careful.careful and not normal.careful
    a, _, _ = normal.run(s, count, np.zeros(3), np.zeros(3))
    b, _, _ = careful.run(s, count, np.zeros(3), np.zeros(3))
    scale = normal.system.layout.length_scale
    assert np.max(np.abs(a.q - b.q)) < 1e-11 * scale
    assert np.max(np.abs(a.qd - b.qd)) * h / 2 < 1e-11 * scale
    assert normal.slow_steps == 0 and careful.slow_steps == count
    careful.careful = False
    careful.run(b, 3, np.zeros(3), np.zeros(3))
    assert careful.slow_steps == count


def test_a_step_of_another_length_is_the_plain_step_at_that_length() -> None:
    """Two compiled steps of h/2 from a state against the plain step built with h/2 (its penalties
    4 times larger: the same converged state); h itself is back afterwards, so the next step is
    a step of h."""
    h = 1e-3
    compiled, s = _start(True, h)
    plain, _ = _start(False, h / 2)
    assert isinstance(compiled, CompiledAli3p) and not isinstance(plain, CompiledAli3p)
    a, _, _ = compiled.run_length(s, h / 2, np.zeros(3), np.zeros(3))
    a, _, _ = compiled.run_length(a, h / 2, np.zeros(3), np.zeros(3))
    b = plain.step(plain.step(s))
    scale = plain.system.layout.length_scale
    assert a.t == b.t == h
    assert np.max(np.abs(a.q - b.q)) < 1e-11 * scale
    assert np.max(np.abs(a.qd - b.qd)) * h / 2 < 1e-11 * scale
    assert compiled.params[compiled.kernels.P_H] == h
    assert compiled.step(a).t == 2 * h
