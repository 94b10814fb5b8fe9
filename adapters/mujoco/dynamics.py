"""MuJoCo in free dynamics: its settings, the start velocity from the bodies' rates, the motors'
controls over time and the extra angle columns.

The loop closures are MuJoCo's soft `connect` equalities: solref's time constant sets how fast a
violation is pulled back, solimp's impedance how much of the exact constraint force MuJoCo applies.
The settings, the same rule as in kinematics, are adapters.mujoco.settings'.
"""

from __future__ import annotations

import mujoco
import numpy as np

from adapters.base import Singular
from adapters.mujoco.tree import TreeError, plan_tree
from scenarios.scenario import Scenario

DYNAMIC_MODES = ("RK4", "implicit", "implicitfast", "Euler")


def closes_loops(scenario: Scenario) -> bool:
    """Whether MuJoCo closes a loop with a soft equality (an open chain has nothing to soften)."""
    try:
        return bool(plan_tree(scenario).closures)
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
