"""MuJoCo's kinematic mode: Newton on MuJoCo's own constraint rows at each grid time.

MuJoCo integrates soft constraints; its constraint rows (efc_pos, efc_J, made by mj_fwdPosition)
are nevertheless the exact kinematics of its model. Here the clocks are set to their exact motion
at each grid time and the other dofs are solved on those rows: positions by Newton (warm-started
from the previous time), velocities from J v = 0 with the clocks' rates, accelerations from
J a = -(dJ/dt) v, the bias dJ/dt v read from MuJoCo itself (the site accelerations of each
connect at qacc = 0) or, for a joint or tendon equality y = P(x) with a quartic P (a polynomial
drive), -P''(x) x'^2 from its polycoef and MuJoCo's x and x' (linear ones have none). What this measures is
MuJoCo's kinematics, solved by a loop in the adapter: the levels above position are adapter solves.
"""

from __future__ import annotations

import mujoco
import numpy as np

from adapters.base import Singular, Unsupported
from adapters.mujoco.laws import Clock
from adapters.mujoco.pairs import collides

NEWTON_STEP = 1e-14
"""Newton stops when its step is below this, per unit of each dof's size (1 rad, the extent)."""
ITERATIONS = 30
EQUALITY = int(mujoco.mjtConstraint.mjCNSTR_EQUALITY)
CONNECT, JOINT, TENDON = (
    int(k) for k in (mujoco.mjtEq.mjEQ_CONNECT, mujoco.mjtEq.mjEQ_JOINT, mujoco.mjtEq.mjEQ_TENDON)
)


def check_rows(m: mujoco.MjModel) -> str | None:
    """Why the kinematic mode cannot solve this model's rows exactly, if it cannot."""
    if collides(m):
        return "MuJoCo's kinematic mode solves equality rows only; a cam is a contact (use RK4)"
    for k in range(m.neq):
        kind = int(m.eq_type[k])
        if kind == CONNECT and m.eq_objtype[k] != int(mujoco.mjtObj.mjOBJ_SITE):
            return "a body-anchored connect (the kinematic mode reads site accelerations)"
        if kind not in (JOINT, TENDON, CONNECT):
            return f"an equality of MuJoCo type {kind}"
    return None


class KinematicSolver:
    """Solves MuJoCo's rows at given times on one MjData (clocks: dof -> exact clock motion)."""

    def __init__(self, m: mujoco.MjModel, clocks: dict[int, Clock], sizes: np.ndarray) -> None:
        reason = check_rows(m)
        if reason:
            raise Unsupported(reason)
        self.m, self.clocks, self.sizes = m, clocks, sizes
        self.fixed = np.array(sorted(clocks), dtype=int)
        self.free = np.array([k for k in range(m.nv) if k not in clocks], dtype=int)
        self.six = np.empty(6)

    def solve(self, d: mujoco.MjData, t: float) -> None:
        """d.qpos, d.qvel and d.qacc on MuJoCo's rows at time t, with d's kinematics, velocities
        and accelerations (cacc) computed: ready for mj_objectVelocity/mj_objectAcceleration."""
        m = self.m
        d.time = t
        clock_acc = np.zeros(len(self.fixed))
        for i, dof in enumerate(self.fixed):
            clock = self.clocks[int(dof)]
            d.qpos[dof], d.qvel[dof] = clock.at(t)
            clock_acc[i] = clock.acc(t)
        jac = self._positions(d, t)
        d.qvel[self.free] = _solve(jac[:, self.free], -jac[:, self.fixed] @ d.qvel[self.fixed])
        mujoco.mj_fwdVelocity(m, d)
        d.qacc[:] = 0.0
        mujoco.mj_rnePostConstraint(m, d)
        bias = self._bias(d)
        d.qacc[self.fixed] = clock_acc
        d.qacc[self.free] = _solve(jac[:, self.free], -bias - jac[:, self.fixed] @ clock_acc)
        mujoco.mj_rnePostConstraint(m, d)

    def _positions(self, d: mujoco.MjData, t: float) -> np.ndarray:
        """Newton on the equality rows; returns their Jacobian at the solution."""
        m = self.m
        for _ in range(ITERATIONS):
            mujoco.mj_fwdPosition(m, d)
            rows = d.efc_type == EQUALITY
            jac = d.efc_J.reshape(d.nefc, m.nv)[rows]
            step = _solve(jac[:, self.free], -d.efc_pos[rows])
            d.qpos[self.free] += step
            if np.max(np.abs(step) / self.sizes[self.free], initial=0.0) < NEWTON_STEP:
                mujoco.mj_fwdPosition(m, d)
                return d.efc_J.reshape(d.nefc, m.nv)[d.efc_type == EQUALITY].copy()
        raise Singular(f"Newton on MuJoCo's rows did not converge at t = {t:.6g} s", t)

    def _bias(self, d: mujoco.MjData) -> np.ndarray:
        """dJ/dt v of each equality row: for a site connect, the difference of the two sites'
        accelerations at qacc = 0 (d.cacc computed at qacc = 0); for a joint or tendon equality
        y - a0 - a1 x - ... - a4 x^4 (x measured from its reference), -P''(x) x'^2."""
        m = self.m
        rows = np.flatnonzero(d.efc_type == EQUALITY)
        bias = np.zeros(len(rows))
        done: set[int] = set()
        for i, row in enumerate(rows):
            eq = int(d.efc_id[row])
            if int(m.eq_type[eq]) in (JOINT, TENDON):
                bias[i] = self._polynomial_bias(d, eq)
                continue
            if eq in done:
                continue
            done.add(eq)
            bias[i : i + 3] = self._site_acc(d, m.eq_obj1id[eq]) - self._site_acc(d, m.eq_obj2id[eq])
        return bias

    def _polynomial_bias(self, d: mujoco.MjData, eq: int) -> float:
        """-P''(x) x'^2 of a joint or tendon equality (0 without a second joint or tendon)."""
        m = self.m
        a, second = m.eq_data[eq, :5], int(m.eq_obj2id[eq])
        if second < 0 or not np.any(a[2:] != 0.0):
            return 0.0
        if int(m.eq_type[eq]) == JOINT:
            x = d.qpos[m.jnt_qposadr[second]] - m.qpos0[m.jnt_qposadr[second]]
            rate = d.qvel[m.jnt_dofadr[second]]
        else:
            x, rate = d.ten_length[second] - m.tendon_length0[second], d.ten_velocity[second]
        curvature = 2.0 * a[2] + 6.0 * a[3] * x + 12.0 * a[4] * x * x
        return float(-curvature * rate * rate)

    def _site_acc(self, d: mujoco.MjData, site: int) -> np.ndarray:
        mujoco.mj_objectAcceleration(self.m, d, mujoco.mjtObj.mjOBJ_SITE, site, self.six, 0)
        return self.six[3:].copy()


def _solve(jac: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """Least squares: MuJoCo's connect rows include the normal (z) row, zero in a planar model."""
    return np.linalg.lstsq(jac, rhs, rcond=None)[0]
