"""The start of a free dynamic run on Pinocchio's model: joint coordinates and rates from the
scenario's assembled body poses and body rates, polished onto Pinocchio's own loop rows.

A free mechanism has more joint coordinates than loop rows, so the polish takes minimum-norm Newton
steps (a least-squares solve on the row Jacobian) and the rates are the joint rates that reproduce
the bodies' (vx, vy, omega) through Pinocchio's frame Jacobians, projected onto the loop rows'
velocity constraints (the nearest consistent rates in the joint-rate norm).
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from adapters.base import EngineFailure
from adapters.pinocchio.kinematics import KinematicSolver
from adapters.pinocchio.model import frame_jacobian
from scenarios.bodies import Point
from scenarios.scenario import Scenario

POLISH = 5
"""Newton steps at most; the scenarios' guesses are assembled to round-off already."""
ROUNDOFF = 1e-14
"""A loop residual below this fraction of the characteristic length is assembled."""


def free_start(scenario: Scenario, kin: KinematicSolver) -> tuple[np.ndarray, np.ndarray]:
    """(q0, v0) consistent with the loop rows, from the scenario's body guesses and rates."""
    pm = kin.pm
    q = pm.q_guess()
    if kin.constraint_rows.closures:
        for _ in range(POLISH):
            rows = kin.constraint_rows.evaluate(kin.snapshot(q))
            if float(np.max(np.abs(rows.val))) <= ROUNDOFF * scenario.characteristic_length:
                break
            q = q + np.linalg.lstsq(rows.jac, -rows.val, rcond=None)[0]
        else:
            raise EngineFailure("cannot assemble the start on Pinocchio's loop rows", 0.0)
    model, data = pm.model, kin.data
    pin.computeJointJacobians(model, data, q)
    pin.updateFramePlacements(model, data)
    jac = np.concatenate(
        [
            np.vstack([frame_jacobian(model, data, pm.frame_id[Point(b.name)])[:2], pm.angle_row[b.name]])
            for b in scenario.bodies
        ]
    )
    rates = np.concatenate([np.asarray(b.rate, dtype=float) for b in scenario.bodies])
    v = np.linalg.lstsq(jac, rates, rcond=None)[0]
    if kin.constraint_rows.closures:
        loop = kin.constraint_rows.evaluate(kin.snapshot(q)).jac
        v = v - loop.T @ np.linalg.lstsq(loop @ loop.T, loop @ v, rcond=None)[0]
    return q, v
