"""MuJoCo as a new user's model has it: the engine's own defaults, read from the engine, for
everything a model of the mechanism need not set (integrator, solref, solimp, the solver's tolerance
and iterations, the regulariser), at the step the rule gives. What the mechanism needs to be
modelled at all (its clocks, cam followers' preload springs, the consistent start) stays ours."""

from __future__ import annotations

from dataclasses import replace

import mujoco
import numpy as np

from adapters.mujoco.mjcf import Physics
from adapters.mujoco.weights import MUJOCO_S_OWN

INTEGRATORS = {
    mujoco.mjtIntegrator.mjINT_EULER: "Euler",
    mujoco.mjtIntegrator.mjINT_RK4: "RK4",
    mujoco.mjtIntegrator.mjINT_IMPLICIT: "implicit",
    mujoco.mjtIntegrator.mjINT_IMPLICITFAST: "implicitfast",
}
"""MJCF's names of MuJoCo's integrators."""


def untuned(physics: Physics) -> Physics:
    """`physics` (its step, clocks, springs, loads and cams) with MuJoCo's own defaults for the
    integrator, every constraint's solref and solimp, the solver and the regulariser."""
    empty = mujoco.MjModel.from_xml_string("<mujoco/>")
    solref, solimp = np.zeros(mujoco.mjNREF), np.zeros(mujoco.mjNIMP)
    mujoco.mj_defaultSolRefImp(solref, solimp)
    ref = (float(solref[0]), float(solref[1]))
    imp = (float(solimp[0]), float(solimp[1]), float(solimp[2]), float(solimp[3]), float(solimp[4]))
    return replace(
        physics,
        integrator=INTEGRATORS[mujoco.mjtIntegrator(empty.opt.integrator)],
        solref=ref,
        contact_solref=ref,
        solimp=imp,
        contact_solimp=imp,
        tolerance=float(empty.opt.tolerance),
        iterations=int(empty.opt.iterations),
        invweight=MUJOCO_S_OWN,
    )
