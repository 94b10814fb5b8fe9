"""ALI3-P over a time grid: equal steps of at most the given size over the whole span, whatever the
grid (an output interval far shorter than the step, such as a singular passage's time put next to
a grid point, would otherwise force a tiny step, where the index-3 rates 2/h q and 4/h^2 q lose
their digits to cancellation). Outputs between steps come from the quintic Hermite interpolant of
q, q' and q'' at the two ends, whose own error, O(h^6), is far below the method's O(h^2); the work
integrals are the trapezoidal quadrature of the powers, interpolated linearly between steps.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from reference_solver.dynamics.ali3p import Ali3p, StepState
from reference_solver.dynamics.compiled_ali3p import CompiledAli3p, ali3p_stepper
from reference_solver.dynamics.loads import Loads
from reference_solver.dynamics.partition import State, driver_power
from reference_solver.system import ConstraintSystem

# p(s) = sum c_j s^j on [0, 1] from p, p', p'' at both ends: c = HERMITE @ [p0, p0', p0'', p1, p1', p1'']
HERMITE = np.linalg.inv(
    np.array(
        [
            [1, 0, 0, 0, 0, 0],
            [0, 1, 0, 0, 0, 0],
            [0, 0, 2, 0, 0, 0],
            [1, 1, 1, 1, 1, 1],
            [0, 1, 2, 3, 4, 5],
            [0, 0, 2, 6, 12, 20],
        ],
        dtype=float,
    )
)
SAME_TIME = 1e-9
"""An output time within this fraction of a step from a step's end is that step's state."""


def integrate(
    system: ConstraintSystem, mass: np.ndarray, loads: Loads, start: State, grid: np.ndarray, step: float
) -> tuple[list[State], np.ndarray, int]:
    """ALI3-P from `start` over `grid` in equal steps of at most `step`: the states at the grid's
    times (with the multipliers at each state, Ali3p.multipliers), the work integrals and the
    number of constraint evaluations."""
    span = float(grid[-1]) - start.t
    count = max(1, int(np.ceil(span / step * (1 - 1e-12))))
    stepper = ali3p_stepper(system, mass, loads, span / count)
    h = stepper.h
    states, works = [start], [np.zeros(3)]
    current = StepState(start.t, start.q, start.qd, start.qdd, start.lam.copy(), start.jac)
    before, power, work = current, _powers(system, start), np.zeros(3)
    work_before, done = work, 0
    for time in grid[1:]:
        # the first step ending at or after this time (within SAME_TIME of a step)
        last = min(count, max(1, int(np.ceil((float(time) - start.t) / h - SAME_TIME))))
        if last > done:
            current, power, work = _advance(stepper, loads, current, last - 1 - done, power, work)
            before, work_before = current, work
            current, power, work = _advance(stepper, loads, current, 1, power, work)
            done = last
            if done == count:  # end exactly on the grid's last time
                current = replace(current, t=float(grid[-1]))
        fraction = min(1.0, (float(time) - before.t) / h)
        point = (
            current
            if fraction >= 1.0 - SAME_TIME
            else _interpolate(system, before, current, fraction, float(time))
        )
        load = loads(point.q, point.qd, point.t).generalized
        states.append(_state(loads, point, stepper.multipliers(point, load)))
        works.append(work_before + fraction * (work - work_before))
    return states, np.array(works), stepper.evaluations


def _advance(
    stepper: Ali3p, loads: Loads, s: StepState, count: int, power: np.ndarray, work: np.ndarray
) -> tuple[StepState, np.ndarray, np.ndarray]:
    """`count` steps from s, the work integrals by the trapezoidal rule on the powers at the steps."""
    if isinstance(stepper, CompiledAli3p):
        return stepper.run(s, count, power, work)
    for _ in range(count):
        s = stepper.step(s)
        now = _powers(stepper.system, _state(loads, s, s.multipliers))
        work = work + stepper.h / 2 * (power + now)
        power = now
    return s, power, work


def _interpolate(
    system: ConstraintSystem, a: StepState, b: StepState, fraction: float, t: float
) -> StepState:
    """The state at `fraction` of the step from a to b on the quintic Hermite interpolant."""
    h = b.t - a.t
    data = np.array([a.q, h * a.qd, h * h * a.qdd, b.q, h * b.qd, h * h * b.qdd])
    coefficients = HERMITE @ data
    s = fraction
    powers = np.array([1, s, s**2, s**3, s**4, s**5])
    slopes = np.array([0, 1, 2 * s, 3 * s**2, 4 * s**3, 5 * s**4])
    curvatures = np.array([0, 0, 2, 6 * s, 12 * s**2, 20 * s**3])
    q = powers @ coefficients
    qd = slopes @ coefficients / h
    qdd = curvatures @ coefficients / (h * h)
    return StepState(t, q, qd, qdd, b.multipliers, system.jacobian(q, t))


def _state(loads: Loads, s: StepState, lam: np.ndarray) -> State:
    """The kinematic State of a step with multipliers `lam`."""
    return State(s.t, s.q, s.qd, s.qdd, lam, s.jac, loads(s.q, s.qd, s.t))


def _powers(system: ConstraintSystem, s: State) -> np.ndarray:
    return np.array([s.loads.applied_power, s.loads.dissipation, driver_power(system, s)])
