"""MuJoCo in free dynamics: its settings, the start velocity from the bodies' rates, the motors'
controls over time and the extra angle columns.

The loop closures are MuJoCo's soft `connect` equalities: solref's time constant (in steps) sets how
fast a violation is pulled back, solimp's impedance how much of the exact constraint force MuJoCo
applies (0.9999, its maximum, by default). The sweep varies the step of each integrator at the
default softness, and the softness at the default step, so each gives a work-precision curve.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager

import mujoco
import numpy as np

from adapters.base import Setting, Singular
from adapters.mujoco.loads import Motor
from adapters.mujoco.tree import TreeError, plan_tree
from scenarios.motions import Constant
from scenarios.scenario import Scenario

DYNAMIC_MODES = ("RK4", "implicit", "implicitfast", "Euler")
DEFAULT = Setting.of("RK4", dt=1e-4, tc_steps=4.0, impedance=0.9999)
LARGE = Setting.of("Euler", dt=5e-3, tc_steps=4.0, impedance=0.9999)
"""The default and only setting beyond BODY_BUDGET bodies: MuJoCo's own default integrator at a
step a MuJoCo user would take (RK4 on the 81-body chain diverges at 5e-3 s, and at 1e-3 s costs
about 4 ms a step, minutes per run)."""
STEP_BUDGET = 1.0e4
"""Steps over the horizon at the finest step of a mode's sweep, so that one scenario's sweep
stays within seconds."""
BODY_BUDGET = 8
RUNGS = {"RK4": 4, "implicit": 3, "implicitfast": 3, "Euler": 3}
"""Steps per mode in the sweep, from the finest the budget allows up in a 1-3-10 ladder."""
SOFTNESS = ((2.0, 0.9999), (16.0, 0.9999), (4.0, 0.99))
"""(tc_steps, impedance) swept with RK4 at the default step beside the default (4, 0.9999)."""


def dynamic_default(scenario: Scenario) -> Setting:
    """RK4 at 1e-4 s (coarser where the horizon needs more than STEP_BUDGET such steps); the
    equalities as stiff as MuJoCo's soft constraints go (impedance 0.9999, its maximum) with a time
    constant of 4 steps: at MuJoCo's minimum of 2 the constraint rings under RK4 (velocity errors
    ten times larger on the free four-bar), beyond 8 the softness shows. Beyond BODY_BUDGET bodies,
    LARGE."""
    if len(scenario.bodies) > BODY_BUDGET:
        return LARGE
    ladder = _ladder(scenario)
    return DEFAULT.replace(dt=max(float(DEFAULT["dt"]), ladder[0])) if ladder else DEFAULT


def dynamic_sweep(scenario: Scenario) -> list[Setting]:
    """Each integrator over a 1-3-10 ladder of steps from the finest its budget allows up to the
    output interval (the engine step divides it), at the default softness; then, where a loop is
    closed, RK4's softness (solref time constant, solimp) at the default step. Beyond BODY_BUDGET
    bodies, the default alone."""
    default = dynamic_default(scenario)
    if default is LARGE:
        return [LARGE]
    ladder = _ladder(scenario)
    settings = [
        Setting(mode, default.options).replace(dt=dt)
        for mode, rungs in RUNGS.items()
        for dt in ladder[:rungs]
    ]
    if _closes_loops(scenario):
        settings += [default.replace(tc_steps=tc, impedance=imp) for tc, imp in SOFTNESS]
    return settings


def _ladder(scenario: Scenario) -> list[float]:
    """Steps of 1, 3, 10, 30 ... from the finest keeping the horizon within STEP_BUDGET steps up to
    the output interval."""
    times = scenario.times()
    finest = float(times[-1] - times[0]) / STEP_BUDGET
    interval = float(times[1] - times[0]) if len(times) > 1 else np.inf
    return [
        step
        for step in (c * 10.0**e for e in range(-9, 0) for c in (1.0, 3.0))
        if finest * (1 - 1e-9) <= step <= interval * (1 + 1e-9)
    ]


def _closes_loops(scenario: Scenario) -> bool:
    """Whether MuJoCo closes a loop with a soft equality (an open chain has nothing to soften)."""
    try:
        return bool(plan_tree(scenario).loops)
    except TreeError:
        return False


def rate_velocities(m: mujoco.MjModel, d: mujoco.MjData, sites: list[int], rates: np.ndarray) -> None:
    """d.qvel from the bodies' frame rates (vx, vy, omega per site): a least-squares solve of the
    site Jacobians, Singular if the rates are not those of one joint velocity."""
    mujoco.mj_kinematics(m, d)
    mujoco.mj_comPos(m, d)
    rows = []
    jacp, jacr = np.empty((3, m.nv)), np.empty((3, m.nv))
    for site in sites:
        mujoco.mj_jacSite(m, d, jacp, jacr, site)
        rows += [jacp[0].copy(), jacp[1].copy(), jacr[2].copy()]
    jac = np.array(rows).reshape(-1, m.nv)
    d.qvel[:] = np.linalg.lstsq(jac, rates.ravel(), rcond=None)[0]
    residual = float(np.abs(jac @ d.qvel - rates.ravel()).max(initial=0.0))
    if residual > 1e-9 * max(1.0, float(np.abs(rates).max(initial=0.0))):
        raise Singular(f"the bodies' start rates are not one joint velocity (residual {residual:.3g})", 0.0)
    mujoco.mj_forward(m, d)


@contextmanager
def controls(m: mujoco.MjModel, d: mujoco.MjData, motors: tuple[Motor, ...]) -> Iterator[None]:
    """The motors' controls: constant ones set once; time-varying ones evaluated by MuJoCo's control
    callback at every stage's time (RK4 calls it at its stage times), removed afterwards."""
    ids = [mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_ACTUATOR, motor.name) for motor in motors]
    varying = [
        (i, motor.law) for i, motor in zip(ids, motors, strict=True) if not isinstance(motor.law, Constant)
    ]
    for i, motor in zip(ids, motors, strict=True):
        d.ctrl[i] = motor.law.f(d.time)
    if not varying:
        yield
        return

    def control(_: mujoco.MjModel, data: mujoco.MjData) -> None:
        for i, law in varying:
            data.ctrl[i] = law.f(data.time)

    mujoco.set_mjcb_control(control)
    try:
        yield
    finally:
        mujoco.set_mjcb_control(None)


def angle_columns(scenario: Scenario, bodies: tuple[str, ...], theta: np.ndarray) -> dict[str, np.ndarray]:
    """The scenario's angle outputs from the output bodies' angles (n x bodies); those naming a
    body not output are left out."""
    column = {body: theta[:, k] for k, body in enumerate(bodies)}
    column["ground"] = np.zeros(len(theta))
    return {
        a.name: column[a.body] - column[a.relative_to]
        for a in scenario.angle_outputs
        if a.body in column and a.relative_to in column
    }
