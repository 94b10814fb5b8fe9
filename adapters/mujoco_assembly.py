"""Consistent initial state from MuJoCo's own constraint rows.

MuJoCo does not assemble a closed loop: it starts wherever qpos is and lets the soft constraints
pull it shut, which is a transient, not the mechanism. So the start is solved on MuJoCo's rows:
Newton on the equality and contact residuals (efc_pos) with their Jacobian (efc_J) for the
positions, then the velocity rows J v = 0 for qvel, with the clocks held at their own values.
"""

from __future__ import annotations

import mujoco
import numpy as np

from adapters.base import Singular

CAM_MARGIN = 0.05
"""Contact detection distance while assembling, so that a separated cam contact still has a row."""

ROWS = (mujoco.mjtConstraint.mjCNSTR_EQUALITY, mujoco.mjtConstraint.mjCNSTR_CONTACT_FRICTIONLESS)


def _rows(m: mujoco.MjModel, d: mujoco.MjData) -> tuple[np.ndarray, np.ndarray]:
    """Residuals and their Jacobian (rows x dofs) of the equalities and contacts."""
    mujoco.mj_forward(m, d)
    keep = np.isin(d.efc_type, ROWS)
    jac = d.efc_J.reshape(d.nefc, m.nv)
    return d.efc_pos[keep].copy(), jac[keep].copy()


def assemble(
    m: mujoco.MjModel,
    d: mujoco.MjData,
    clocks: dict[int, tuple[float, float]],
    tolerance: float = 1e-13,
    iterations: int = 50,
) -> None:
    """Solve d.qpos and d.qvel in place. `clocks` maps a clock's dof to its (qpos, qvel); MuJoCo's
    dofs and qpos coincide here (hinges and slides only)."""
    margin = m.pair_margin.copy()
    m.pair_margin[:] = CAM_MARGIN
    try:
        free = np.array([k for k in range(m.nv) if k not in clocks], dtype=int)
        fixed = np.array(sorted(clocks), dtype=int)
        for dof, (q, v) in clocks.items():
            d.qpos[dof], d.qvel[dof] = q, v
        residual = np.inf
        for _ in range(iterations):
            pos, jac = _rows(m, d)
            residual = float(np.max(np.abs(pos), initial=0.0))
            if residual < tolerance:
                break
            step = np.linalg.lstsq(jac[:, free], -pos, rcond=None)[0]
            d.qpos[free] += step
        else:
            raise Singular(f"the mechanism does not assemble in MuJoCo (residual {residual:.3g})", 0.0)
        pos, jac = _rows(m, d)
        rhs = -jac[:, fixed] @ d.qvel[fixed] if fixed.size else np.zeros(len(pos))
        d.qvel[free] = np.linalg.lstsq(jac[:, free], rhs, rcond=None)[0]
        velocity_residual = np.abs(jac @ d.qvel).max(initial=0.0)
        scale = max(1.0, float(np.abs(d.qvel).max()))
        if velocity_residual > 1e-9 * scale:
            raise Singular(f"the start velocity is not unique (residual {velocity_residual:.3g})", 0.0)
    finally:
        m.pair_margin[:] = margin
    mujoco.mj_forward(m, d)


def contact_slopes(m: mujoco.MjModel, d: mujoco.MjData) -> dict[int, np.ndarray]:
    """For each contact pair (by index), the gradient of its distance over the dofs."""
    margin = m.pair_margin.copy()
    m.pair_margin[:] = CAM_MARGIN
    try:
        mujoco.mj_forward(m, d)
        jac = d.efc_J.reshape(d.nefc, m.nv)
        slopes: dict[int, np.ndarray] = {}
        for i in range(d.ncon):
            contact = d.contact[i]
            pair = _pair_index(m, contact.geom1, contact.geom2)
            if pair is not None and contact.efc_address >= 0:
                slopes.setdefault(pair, jac[contact.efc_address].copy())
    finally:
        m.pair_margin[:] = margin
    mujoco.mj_forward(m, d)
    return slopes


def _pair_index(m: mujoco.MjModel, g1: int, g2: int) -> int | None:
    for k in range(m.npair):
        if {int(m.pair_geom1[k]), int(m.pair_geom2[k])} == {g1, g2}:
            return k
    return None


def settle(
    m: mujoco.MjModel, d: mujoco.MjData, clocks: dict[int, tuple[float, float]], steps: int = 400
) -> None:
    """Let preloaded contacts sink to their static penetration with the drives held still, then
    give the mechanism its start velocity again (MuJoCo's contact carries load only when it
    penetrates, so an assembled contact at distance zero would start with a jolt)."""
    start = {dof: (q, 0.0) for dof, (q, _) in clocks.items()}
    for dof, (q, _) in start.items():
        d.qpos[dof], d.qvel[dof] = q, 0.0
    d.qvel[:] = 0.0
    mujoco.mj_step(m, d, steps)
    if not np.isfinite(d.qpos).all():
        raise Singular("the preloaded cam contact does not settle", 0.0)
    d.time = 0.0
    d.qvel[:] = 0.0
    fixed = np.array(sorted(clocks), dtype=int)
    free = np.array([k for k in range(m.nv) if k not in clocks], dtype=int)
    for dof, (q, v) in clocks.items():
        d.qpos[dof], d.qvel[dof] = q, v
    _, jac = _rows(m, d)
    d.qvel[free] = np.linalg.lstsq(jac[:, free], -jac[:, fixed] @ d.qvel[fixed], rcond=None)[0]
    mujoco.mj_forward(m, d)
