"""Fixed-step time marching around Pinocchio's accelerations, as Pinocchio's users write it.

Pinocchio computes accelerations (aba, constraintDynamics, forwardDynamics) and moves a
configuration along a velocity (`pin.integrate`); it has no integrator of its own. Its users wrap
them in one of two loops, offered here:
- `rk4`: the classical fourth-order Runge-Kutta method on (q, v), four accelerations per step;
- `euler`: semi-implicit (symplectic) Euler, v += h a(q, v) then q = integrate(q, h v), first
  order, one acceleration per step: the loop of Pinocchio's own simulation examples.
The march takes whole steps `dt` from the first output time, whatever the grid; an output time
between two steps is reached by a side step from the lattice (adapters.lattice), so the grid changes
where outputs are read, never the states the march goes through.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from adapters.base import MAX_STEPS, Diverged, EngineFailure
from adapters.lattice import check_grid, lattice_point

RK4, EULER = "rk4", "euler"
BLOWUP = 1e8
"""A joint speed above this (rad/s or m/s) counts as diverged."""
"""More steps than this in one run is a step size typed by mistake, refused before marching."""

Acceleration = Callable[[float, np.ndarray, np.ndarray], np.ndarray]
"""a(t, q, v)."""
Integrate = Callable[[np.ndarray, np.ndarray], np.ndarray]
"""q moved along the velocity increment dq (`pin.integrate(model, q, dq)`)."""
State = tuple[np.ndarray, np.ndarray, np.ndarray]
"""q, v and a = a(t, q, v)."""


def rk4_step(acc: Acceleration, move: Integrate, t: float, h: float, state: State) -> State:
    """One classical Runge-Kutta step; the new state's acceleration is the next step's first stage."""
    q, v, a = state
    q2, v2 = move(q, 0.5 * h * v), v + 0.5 * h * a
    a2 = acc(t + 0.5 * h, q2, v2)
    q3, v3 = move(q, 0.5 * h * v2), v + 0.5 * h * a2
    a3 = acc(t + 0.5 * h, q3, v3)
    q4, v4 = move(q, h * v3), v + h * a3
    a4 = acc(t + h, q4, v4)
    q_new = move(q, h / 6.0 * (v + 2.0 * v2 + 2.0 * v3 + v4))
    v_new = v + h / 6.0 * (a + 2.0 * a2 + 2.0 * a3 + a4)
    return q_new, v_new, acc(t + h, q_new, v_new)


def euler_step(acc: Acceleration, move: Integrate, t: float, h: float, state: State) -> State:
    """One semi-implicit Euler step: the velocity first, then the configuration with the new velocity."""
    q, v, a = state
    v_new = v + h * a
    q_new = move(q, h * v_new)
    return q_new, v_new, acc(t + h, q_new, v_new)


STEPS: dict[str, Callable[[Acceleration, Integrate, float, float, State], State]] = {
    RK4: rk4_step,
    EULER: euler_step,
}


def march(
    acc: Acceleration, move: Integrate, start: State, times: np.ndarray, dt: float, method: str
) -> tuple[np.ndarray, np.ndarray, np.ndarray, int]:
    """q, v and a at every output time from `start` at times[0], and the number of steps taken."""
    step = STEPS[method]
    n = len(times)
    planned = (float(times[-1]) - float(times[0])) / dt if n > 1 else 0.0
    if planned > MAX_STEPS:
        raise EngineFailure(f"dt = {dt:.3g} s would take {planned:.3g} steps (more than {MAX_STEPS:.0e})")
    check_grid(times, float(times[0]))
    out = np.zeros((3, n, start[0].size))
    out[:, 0] = start
    state, t0, done = start, float(times[0]), 0
    for k in range(1, n):
        whole, rest = lattice_point(t0, float(times[k]), dt)
        for i in range(done, whole):
            state = step(acc, move, t0 + i * dt, dt, state)
        done = max(done, whole)
        reached = step(acc, move, t0 + whole * dt, rest, state) if rest > 0.0 else state
        if not (np.all(np.isfinite(reached[2])) and np.max(np.abs(reached[1]), initial=0.0) < BLOWUP):
            t = float(times[k])  # checked once per output: the check costs as much as a step's vector work
            raise Diverged(f"{method.upper()} on Pinocchio's dynamics diverged by t = {t:.6g}", t)
        out[:, k] = reached
    side = sum(1 for k in range(1, n) if lattice_point(t0, float(times[k]), dt)[1] > 0.0)
    return out[0], out[1], out[2], done + side
