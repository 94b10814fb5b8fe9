"""Spies on ALI3-P's grid near a singular passage: the schedule of steps the compiled stepper is asked
for, and a careful step made to fail."""

from __future__ import annotations

import pytest

import scenarios
from reference_solver.compiled_system import constraint_system
from reference_solver.dynamics import ali3p_schedule
from reference_solver.dynamics.ali3p import StepState
from reference_solver.dynamics.compiled_ali3p import CompiledAli3p, ali3p_stepper
from reference_solver.dynamics.forward import initial_state
from reference_solver.dynamics.loads import Loads
from reference_solver.dynamics.mass import mass_diagonal
from reference_solver.errors import ConvergenceError


def compiled_schedule(
    scenario: scenarios.Scenario,
) -> tuple[CompiledAli3p, StepState, ali3p_schedule.Schedule]:
    """The compiled ALI3-P stepper of `scenario` at h = 1e-3, its assembled start and a schedule of
    10 steps over 0.01 s from it, without a watch."""
    system = constraint_system(scenario)
    mass = mass_diagonal(scenario, system.layout)
    loads = Loads(scenario, system.layout, mass)
    start = initial_state(system, mass, loads, 0.0)
    first = StepState(start.t, start.q, start.qd, start.qdd, start.lam.copy(), start.jac)
    stepper = ali3p_stepper(system, mass, loads, 1e-3)
    assert isinstance(stepper, CompiledAli3p)
    return stepper, first, ali3p_schedule.Schedule(stepper, loads, first, 10, 0.01, None)


def fail_when_careful(monkeypatch: pytest.MonkeyPatch, stepper: CompiledAli3p, time: float) -> None:
    """From now on, the stepper's careful steps raise (as a Schur complement next to an instant the
    watch did not predict may); it is careful now."""
    run = stepper.run

    def failing(*args: object) -> object:
        if stepper.careful:
            raise ConvergenceError("careful step failed", time=time)
        return run(*args)  # type: ignore[arg-type]

    monkeypatch.setattr(stepper, "run", failing)
    stepper.careful = True
