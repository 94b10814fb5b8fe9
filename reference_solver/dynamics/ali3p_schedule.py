"""ALI3-P's steps over a span: `count` equal steps of h from t0, except around a singular passage,
which the compiled step watches for (dynamics.passage): there the steps are careful (through the
Schur complement from their first iteration) while PENALTY s^2 < passage.CAREFUL, and the two steps
around the predicted instant become three, [t_j, t* - h/2], [t* - h/2, t* + h/2], [t* + h/2,
t_{j+3}] (each 0.5 to 1.5 h long), so that no step ends within half a step of it and the grid
resumes at t_{j+3}. The plain step (dynamics.ali3p) keeps its equal steps.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from reference_solver.dynamics.ali3p import Ali3p, StepState
from reference_solver.dynamics.compiled_ali3p import CompiledAli3p
from reference_solver.dynamics.loads import Loads
from reference_solver.dynamics.partition import State, driver_power
from reference_solver.dynamics.passage import END_VALUE, Watch
from reference_solver.errors import ConvergenceError
from reference_solver.system import ConstraintSystem

SAME_TIME = 1e-9
"""An output time within this fraction of a step from a step's end is that step's state."""


class Schedule:
    """The stepping state: the last step's two ends (`before`, `state`), the powers at `state`
    and the work integrals at both ends."""

    def __init__(
        self, stepper: Ali3p, loads: Loads, start: StepState, count: int, end: float, watch: Watch | None
    ) -> None:
        self.stepper, self.loads, self.count, self.end = stepper, loads, count, end
        self.t0, self.h = start.t, stepper.h
        self.watch = watch if isinstance(stepper, CompiledAli3p) else None
        self.state = self.before = start
        self.power = powers(stepper.system, state_of(loads, start, start.multipliers))
        self.work = self.work_before = np.zeros(3)
        self.k = 0
        """The grid index of `state` (its last one while placed steps are under way)."""
        self.queue: list[float] = []
        self.check_at = 0
        self.place_at: int | None = None
        self.zero = math.nan
        self.half = self.h / 2
        self.resume = 0

    def advance(self, until: float) -> None:
        """Steps until a step ends at or after `until` (within SAME_TIME of a step)."""
        h, t0 = self.h, self.t0
        while self.state.t < until - SAME_TIME * h:
            if self.queue:
                self._take(1, self.queue.pop(0) - self.state.t)
                if not self.queue:
                    self.k = self.resume
                continue
            if self.watch is not None and self.k >= self.check_at:
                self._check()
                continue
            if self.place_at == self.k:
                self._place()
                continue
            last = min(self.count, max(self.k + 1, math.ceil((until - t0) / h - SAME_TIME)))
            stop = min(last, self.check_at if self.watch is not None else last)
            if self.place_at is not None:
                stop = min(stop, self.place_at)
            if stop - self.k > 1:
                self._take(stop - self.k - 1, None)
            self._take(1, None)
            self.k = stop
            if self.k == self.count:  # end exactly on the span's last time
                self.state = replace(self.state, t=self.end)

    def _take(self, count: int, length: float | None) -> None:
        """`count` steps of h, or one of `length`; a careful step that fails is taken again
        without care (the Schur complement next to an instant it could not predict)."""
        self.before, self.work_before = self.state, self.work
        stepper = self.stepper
        if not isinstance(stepper, CompiledAli3p):
            for _ in range(count):
                self.state = stepper.step(self.state)
                now = powers(stepper.system, state_of(self.loads, self.state, self.state.multipliers))
                self.work = self.work + stepper.h / 2 * (self.power + now)
                self.power = now
            return
        try:
            self.state, self.power, self.work = self._run(count, length)
        except (ConvergenceError, np.linalg.LinAlgError):
            if not stepper.careful:
                raise
            stepper.careful = False
            self.state, self.power, self.work = self._run(count, length)

    def _run(self, count: int, length: float | None) -> tuple[StepState, np.ndarray, np.ndarray]:
        stepper = self.stepper
        assert isinstance(stepper, CompiledAli3p)
        if length is None:
            return stepper.run(self.state, count, self.power, self.work)
        return stepper.run_length(self.state, length, self.power, self.work)

    def _check(self) -> None:
        """Read s; set the steps' care; predict the instant and where to place steps around it."""
        watch, stepper = self.watch, self.stepper
        assert watch is not None and isinstance(stepper, CompiledAli3p)
        watch.read(self.state.t, self.state.jac)
        stepper.careful = watch.careful
        predicted = watch.zero()
        self.place_at = None
        if watch.careful and predicted is not None:
            zero, slope = predicted
            half = max(self.h, 2 * END_VALUE / slope) / 2
            j = math.floor((zero - half - self.t0) / self.h - 0.5)
            resume = math.ceil((zero + half - self.t0) / self.h + 0.5)
            if self.k <= j and resume <= self.count:
                self.place_at, self.zero, self.half, self.resume = j, zero, half, resume
        self.check_at = self.k + watch.steps_to_check(self.h)

    def _place(self) -> None:
        """Three steps from t_j around the predicted instant, back to the grid at t_{j+3}."""
        assert self.watch is not None
        back = self.end if self.resume == self.count else self.t0 + self.resume * self.h
        self.queue = [self.zero - self.half, self.zero + self.half, back]
        self.place_at = None
        self.watch.forget()
        self.check_at = self.resume


def state_of(loads: Loads, s: StepState, lam: np.ndarray) -> State:
    """The kinematic State of a step with multipliers `lam`."""
    return State(s.t, s.q, s.qd, s.qdd, lam, s.jac, loads(s.q, s.qd, s.t))


def powers(system: ConstraintSystem, s: State) -> np.ndarray:
    """The applied, dissipated and driver powers at a state."""
    return np.array([s.loads.applied_power, s.loads.dissipation, driver_power(system, s)])
