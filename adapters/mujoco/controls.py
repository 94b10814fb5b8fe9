"""The controls of a run: the load motors' and the steered clocks', set at every integrator stage.

A steered clock (adapters.mujoco.laws) is a free rotor of inertia I (its armature and its body's own
inertia) started at c(0) = f(0), c'(0) = f'(0); its motor, geared by I, has the control
u = f''(t) (torque I f''(t); a control above 1e10 would be refused by MuJoCo), evaluated at the
time MuJoCo passes, makes c'' = f'' up to the constraint force it feels (a fraction of order
1 / CLOCK_RATIO, adapters.mujoco.scale). MuJoCo calls the control callback (mjcb_control) inside
every forward pass with d.time at that pass's time: RK4 four times per step, at t, t + h/2, t + h/2
and t + h, so RK4 integrates c'' = f''(t) as a quadrature (exact for the piecewise-linear f'' of a
cubic spline within a step; the single-step integrators see f'' at the step's start only, so their
clock lags by O(h)). The callback is process-global: it is set for the run that needs one and
cleared afterwards, whatever happens (the harness forks a process per setting; tests run many
settings in one process).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from functools import partial

import mujoco

from adapters.mujoco.laws import Clock
from adapters.mujoco.loads import Motor
from scenarios.motions import Constant, Motion

Schedule = list[tuple[int, Callable[[float], float]]]
"""(actuator id, its control as a function of time)."""


def clock_inertia(m: mujoco.MjModel, dof: int) -> float:
    """The steered clock's inertia about its axis: armature plus its body's own (the joint sits at
    the body's centre of mass on a principal axis)."""
    return float(m.dof_armature[dof] + m.body_inertia[m.dof_bodyid[dof]][2])


def steering(m: mujoco.MjModel, clocks: dict[int, Clock]) -> Schedule:
    """Each steered clock's motor and its control: f''(t) times the clock's inertia over the motor's
    gear (1: the motor is geared by the inertia, adapters.mujoco.mjcf)."""
    schedule: Schedule = []
    for dof, clock in sorted(clocks.items()):
        law = clock.law
        if law is None:
            continue
        actuator = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_ACTUATOR, clock.joint)
        inertia = clock_inertia(m, dof) / float(m.actuator_gear[actuator, 0])
        schedule.append((actuator, partial(_steer, law, inertia)))
    return schedule


def _steer(law: Motion, inertia: float, t: float) -> float:
    return inertia * law.ddf(t)


@contextmanager
def controls(
    m: mujoco.MjModel,
    d: mujoco.MjData,
    motors: tuple[Motor, ...],
    clocks: dict[int, Clock] | None = None,
    before: float = math.inf,
) -> Iterator[None]:
    """The motors' and steered clocks' controls: constant ones set once, time-varying ones by
    MuJoCo's control callback at every stage's time; the callback is removed afterwards. `before`:
    the laws read just before that time at the latest (the run-in ends at t = 0, where the last
    stage must see the law's left end, not a jump of f'' at a table's start)."""
    latest = math.nextafter(before, -math.inf)
    ids = [mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_ACTUATOR, motor.name) for motor in motors]
    schedule: Schedule = [(i, motor.law.f) for i, motor in zip(ids, motors, strict=True)]
    varying = [s for s, motor in zip(schedule, motors, strict=True) if not isinstance(motor.law, Constant)]
    steered = steering(m, clocks or {})
    varying += steered
    for i, control in schedule + steered:
        d.ctrl[i] = control(min(d.time, latest))
    if not varying:
        yield
        return

    def callback(_: mujoco.MjModel, data: mujoco.MjData) -> None:
        for i, control in varying:
            data.ctrl[i] = control(min(data.time, latest))

    mujoco.set_mjcb_control(callback)
    try:
        yield
    finally:
        mujoco.set_mjcb_control(None)
