"""The start of a free-dynamics run in Exudyn: the scenario's assembled positions and consistent
rates as the system's initial state, and the initial accelerations (with the constraint forces) that
Exudyn's implicit solver computes from them when it initializes, read back once at build time so
that the timed run starts from a complete state."""

from __future__ import annotations

from typing import Any

import exudyn as exu
import numpy as np

from adapters.base import EngineFailure
from adapters.exudyn.assembly import CURRENT, States, write_initial
from adapters.exudyn.model import ExudynModel


def released_start(model: ExudynModel, t0: float, settings: Any) -> States:
    """The scenario's initial positions and rates at `t0`, with Exudyn's own initial accelerations."""
    q0 = np.array(model.guess)
    v0 = np.zeros_like(q0)
    for body in model.scenario.bodies:
        k = model.index[body.name]
        v0[k : k + 3] = body.rate
    write_initial(model, States(q0[None, :], v0[None, :], np.zeros_like(q0)[None, :]))
    ti = settings.timeIntegration
    ti.startTime, ti.endTime, ti.numberOfSteps = t0, t0 + 1.0, 1
    ti.generalizedAlpha.computeInitialAccelerations = True
    solver: Any = exu.MainSolverImplicitSecondOrder()
    try:
        solver.InitializeSolver(model.mbs, settings)
        a0 = np.array(model.mbs.systemData.GetODE2Coordinates_tt(CURRENT))
    except (exu.SolverError, RuntimeError) as error:
        raise EngineFailure(f"Exudyn's initial accelerations: {error}", t0) from error
    finally:
        solver.FinalizeSolver(model.mbs, settings)
    if not np.all(np.isfinite(a0)):
        raise EngineFailure("Exudyn's initial accelerations are not finite", t0)
    start = States(q0[None, :], v0[None, :], a0[None, :])
    write_initial(model, start)
    return start
