"""Stepping a compiled MuJoCo model and reading its outputs: the step and the constraints' solref, a
side step to an output time between two steps, steps with instability caught (`Diverged` with its
time), and each output body's pose, velocity and acceleration from MuJoCo's state."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager

import mujoco
import numpy as np

from adapters.base import Diverged
from adapters.mujoco.model import Model, evaluate

BAD = (mujoco.mjtWarning.mjWARN_BADQACC, mujoco.mjtWarning.mjWARN_BADQPOS, mujoco.mjtWarning.mjWARN_BADQVEL)
STATE = mujoco.mjtState.mjSTATE_INTEGRATION


def soften(m: mujoco.MjModel, model: Model) -> None:
    """The model's step and its equalities' and contacts' solref: a contact's in its explicit pair,
    or in both its geoms where they collide by bits (adapters.mujoco.cams)."""
    m.opt.timestep = model.dt
    m.eq_solref[:] = model.solref
    m.pair_solref[:] = model.contact_solref
    m.geom_solref[(m.geom_contype | m.geom_conaffinity) != 0] = model.contact_solref


@contextmanager
def side_step(m: mujoco.MjModel, d: mujoco.MjData, rest: float) -> Iterator[None]:
    """Inside: the state `rest` seconds on, reached by one step of that length from the lattice
    state (adapters.lattice); after: the lattice state and step again. No step for rest = 0."""
    if rest <= 0.0:
        yield
        return
    state = np.empty(mujoco.mj_stateSize(m, STATE))
    mujoco.mj_getState(m, d, state, STATE)
    step = m.opt.timestep
    m.opt.timestep = rest
    try:
        advance(m, d, 1)
        yield
    finally:
        m.opt.timestep = step
        mujoco.mj_setState(m, d, state, STATE)


def advance(m: mujoco.MjModel, d: mujoco.MjData, steps: int) -> None:
    """`steps` MuJoCo steps; Diverged with the time of the first bad step."""
    state = np.empty(mujoco.mj_stateSize(m, STATE))
    mujoco.mj_getState(m, d, state, STATE)
    mujoco.mj_step(m, d, steps)
    if healthy(d):
        return
    mujoco.mj_setState(m, d, state, STATE)
    for w in BAD:
        d.warning[w].number = 0
    start = d.time
    for _ in range(steps):
        start = d.time
        mujoco.mj_step(m, d)
        if not healthy(d):
            break
    when = f"t = {start:.6g} s" + (" (in the run-in before the start)" if start < 0.0 else "")
    raise Diverged(f"MuJoCo became unstable (bad acceleration) at {when}", float(start))


def healthy(d: mujoco.MjData) -> bool:
    return not any(d.warning[w].number for w in BAD) and bool(np.isfinite(d.qpos).all())


def record(
    m: mujoco.MjModel, d: mujoco.MjData, model: Model, pos: np.ndarray, vel: np.ndarray, acc: np.ndarray
) -> None:
    """Pose, velocity and acceleration of each output body's frame at the current state."""
    mujoco.mj_forward(m, d)
    mujoco.mj_rnePostConstraint(m, d)
    read_outputs(m, d, model, pos, vel, acc)


def read_outputs(
    m: mujoco.MjModel, d: mujoco.MjData, model: Model, pos: np.ndarray, vel: np.ndarray, acc: np.ndarray
) -> None:
    """The outputs from d's computed kinematics, velocities and accelerations (cacc)."""
    six = np.empty(6)
    gx, gy = m.opt.gravity[:2]  # MuJoCo's accelerations carry the world's -gravity
    for k, site in enumerate(model.sites):
        pos[k, :2] = d.site_xpos[site][:2]
        pos[k, 2] = evaluate(model.theta[k], model, d.qpos)
        mujoco.mj_objectVelocity(m, d, mujoco.mjtObj.mjOBJ_SITE, site, six, 0)
        vel[k] = six[3], six[4], six[2]
        mujoco.mj_objectAcceleration(m, d, mujoco.mjtObj.mjOBJ_SITE, site, six, 0)
        acc[k] = six[3] + gx, six[4] + gy, six[2]
