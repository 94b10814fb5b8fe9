"""Stepping a compiled MuJoCo model and reading its outputs: the step that divides the output
interval, the equalities' softness per step, steps with instability caught (`Diverged` with its
time), and each output body's pose, velocity and acceleration from MuJoCo's state."""

from __future__ import annotations

import math

import mujoco
import numpy as np

from adapters.base import Diverged
from adapters.mujoco.model import Model, evaluate

BAD = (mujoco.mjtWarning.mjWARN_BADQACC, mujoco.mjtWarning.mjWARN_BADQPOS, mujoco.mjtWarning.mjWARN_BADQVEL)
STATE = mujoco.mjtState.mjSTATE_INTEGRATION


def engine_step(requested: float, interval: float) -> float:
    """The largest step not above `requested` that divides the output interval."""
    if interval <= 0.0:
        return requested
    return interval / math.ceil(interval / requested - 1e-9)


def output_interval(grid: np.ndarray) -> float:
    if grid.size < 2:
        return 0.0
    steps = np.diff(grid)
    if np.ptp(steps) > 1e-9 * steps.mean() or grid[0] < 0.0:
        raise ValueError("MuJoCo needs an equally spaced time grid from t >= 0")
    return float(steps.mean())


def soften(m: mujoco.MjModel, dt: float, tc_steps: float) -> None:
    m.opt.timestep = dt
    m.eq_solref[:, 0] = tc_steps * dt
    m.pair_solref[:, 0] = tc_steps * dt


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
