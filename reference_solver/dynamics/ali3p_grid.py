"""ALI3-P over a time grid: equal steps of at most the given size over the whole span, whatever the
grid (an output interval far shorter than the step, such as a singular passage's time put next to
a grid point, would otherwise force a tiny step, where the index-3 rates 2/h q and 4/h^2 q lose
their digits to cancellation). Outputs between steps come from the quintic Hermite interpolant of
q, q' and q'' at the two ends, whose own error, O(h^6), is far below the method's O(h^2); the work
integrals are the trapezoidal quadrature of the powers, interpolated linearly between steps.
"""

from __future__ import annotations

import numpy as np

from reference_solver.dynamics.ali3p import StepState
from reference_solver.dynamics.ali3p_schedule import SAME_TIME, Schedule, state_of
from reference_solver.dynamics.compiled_ali3p import ali3p_stepper
from reference_solver.dynamics.loads import Loads
from reference_solver.dynamics.partition import State
from reference_solver.dynamics.passage import Watch
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


def integrate(
    system: ConstraintSystem, mass: np.ndarray, loads: Loads, start: State, grid: np.ndarray, step: float
) -> tuple[list[State], np.ndarray, int]:
    """ALI3-P from `start` over `grid` in equal steps of at most `step` (placed around singular
    passages, ali3p_schedule): the states at the grid's times (with the multipliers at each state,
    Ali3p.multipliers), the work integrals and the number of constraint evaluations."""
    span = float(grid[-1]) - start.t
    count = max(1, int(np.ceil(span / step * (1 - 1e-12))))
    stepper = ali3p_stepper(system, mass, loads, span / count)
    rank = int(np.linalg.matrix_rank(system.scaled_jacobian(start.jac))) if start.jac.size else 0
    first = StepState(start.t, start.q, start.qd, start.qdd, start.lam.copy(), start.jac)
    schedule = Schedule(stepper, loads, first, count, float(grid[-1]), Watch(mass, rank))
    states, works = [start], [np.zeros(3)]
    for time in grid[1:]:
        schedule.advance(float(time))
        before, current = schedule.before, schedule.state
        if current is first:  # no step yet (an output within SAME_TIME of the start): the start
            states.append(start)
            works.append(np.zeros(3))
            continue
        fraction = min(1.0, (float(time) - before.t) / (current.t - before.t))
        point = (
            current
            if fraction >= 1.0 - SAME_TIME
            else _interpolate(system, before, current, fraction, float(time))
        )
        load = loads(point.q, point.qd, point.t).generalized
        states.append(state_of(loads, point, stepper.multipliers(point, load)))
        works.append(schedule.work_before + fraction * (schedule.work - schedule.work_before))
    return states, np.array(works), stepper.evaluations


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
