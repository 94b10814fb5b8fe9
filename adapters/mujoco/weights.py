"""How hard MuJoCo's soft constraints are: the regulariser that holds a closed loop's time constant
short, and so sets how low RK4's error on the constraint mode can be brought.

MuJoCo drives each constraint row's acceleration towards the reference -b (J v) - k r (solref:
b = 2 / (d tc), k = 1 / (d tc)^2 in the time-constant form, b and k themselves in the direct form,
solref = (-k, -b)) and lets it miss by the regulariser R = (1 - d) / d * A_hat, where d is solimp's
impedance (at most 0.9999) and A_hat the row's approximate inverse inertia, built from the compiled
model's `body_invweight0`, `dof_invweight0` and `tendon_invweight0`. Two errors are left on a
closed loop integrated with RK4:
- RK4's error on the constraint mode the time constant creates: the state's velocity across the
  constraint (J qvel) is not the violation's true rate, and b passes the difference into qacc. It
  scales as (dt / tc)^4, so a longer time constant lowers it;
- the regulariser's violation, which grows as tc^2: it holds a longer time constant back while d
  is at its largest.
Scaling the invweight0 of the compiled model by a small factor makes R negligible (a row's R is
what it is scaled by), so tc can be long and the first error goes with it: what is left is the
first error at the longest time constant the loop tolerates (on driven scenes the drive's lag,
in free dynamics the loop's drift, which a long tc no longer pulls back). The factor must be set
right after compiling, before the start is assembled and run in: set later, the start carries the
old model's offset into the run.
"""

from __future__ import annotations

import mujoco

MUJOCO_S_OWN = 1.0
"""The factor leaving MuJoCo's own invweight0 (its regulariser as compiled)."""


def weigh(m: mujoco.MjModel, factor: float) -> None:
    """Scale the model's invweight0 (bodies, dofs, tendons) by `factor`: the regulariser R with it."""
    if factor == MUJOCO_S_OWN:
        return
    m.body_invweight0[:] *= factor
    m.dof_invweight0[:] *= factor
    m.tendon_invweight0[:] *= factor
