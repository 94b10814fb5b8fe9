"""Drake's Simulator over the output grid, read into the canonical trajectory.

SAP's discrete step is q(n+1) = q(n) + h v(n+1): the plant's velocity after a step is the mean over
that step, the derivative at its midpoint. The trajectory's velocity at an output time t is therefore
read (by default) as the mean of the two step velocities around it, the central difference
(q(t + h) - q(t - h)) / 2h of Drake's own positions, and its acceleration as their difference over h,
also centred on t; with `velocity = "state"` the plant's state velocity is given as it is (the
midpoint value of the step before t, what a user reading the state gets). At the first time the
velocity is the assembled start's, exact. Body rates come from the
plant's spatial velocities and accelerations at those generalized values (CalcSpatialAccelerationsFromVdot).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from pydrake.all import Simulator

from adapters.drake.model import Diagram
from adapters.lattice import lattice_point, outputs_on_steps
from scenarios.trajectory import Trajectory

CENTRAL, STATE = "central", "state"


def _read(
    built: Diagram, context: Any, q: np.ndarray, v: np.ndarray, vdot: np.ndarray, bodies: tuple[str, ...]
) -> np.ndarray:
    """(3 levels, bodies, 3): each body frame's pose, velocity and acceleration at (q, v, vdot)."""
    plant = built.plant
    plant.SetPositions(context, q)
    plant.SetVelocities(context, v)
    accelerations = plant.CalcSpatialAccelerationsFromVdot(context, vdot)
    out = np.zeros((3, len(bodies), 3))
    for k, name in enumerate(bodies):
        body = built.bodies[name]
        pose = plant.EvalBodyPoseInWorld(context, body)
        rotation = pose.rotation().matrix()
        out[0, k] = (*pose.translation()[:2], math.atan2(rotation[1, 0], rotation[0, 0]))
        velocity = plant.EvalBodySpatialVelocityInWorld(context, body)
        out[1, k] = (*velocity.translational()[:2], velocity.rotational()[2])
        acceleration = accelerations[int(body.index())]
        out[2, k] = (*acceleration.translational()[:2], acceleration.rotational()[2])
    return out


def run(
    built: Diagram,
    start: tuple[np.ndarray, np.ndarray],
    times: np.ndarray,
    bodies: tuple[str, ...],
    velocity: str,
    guesses: np.ndarray,
) -> tuple[Trajectory, int]:
    """The trajectory on `times` from the consistent `start` (q, v) at times[0], and the steps taken.
    The plant steps on a lattice that puts every output time on a step (adapters.lattice)."""
    h = outputs_on_steps(times, built.dt)
    if not math.isclose(h, built.dt, rel_tol=1e-12):
        raise ValueError(f"the output grid is not on Drake's step lattice (step {built.dt:.6g} s)")
    simulator = Simulator(built.diagram)
    root = simulator.get_mutable_context()
    t0 = float(times[0])
    root.SetTime(t0)
    plant_context = built.plant.GetMyMutableContextFromRoot(root)
    built.plant.SetPositions(plant_context, start[0])
    built.plant.SetVelocities(plant_context, start[1])
    simulator.Initialize()
    reader = built.plant.CreateDefaultContext()
    levels = np.zeros((len(times), 3, len(bodies), 3))
    v_before = start[1].copy()
    steps = 0
    for k, t in enumerate(times):
        n, _ = lattice_point(t0, float(t), h)
        if n > 0:
            simulator.AdvanceTo(t0 + n * h)
        q = built.plant.GetPositions(plant_context).copy()
        v_now = built.plant.GetVelocities(plant_context).copy()
        if n > 0:
            v_before = v_now
        simulator.AdvanceTo(t0 + (n + 1) * h)
        v_after = built.plant.GetVelocities(plant_context).copy()
        steps = n + 1
        if n == 0:  # the assembled start's velocity is exact; the first step's mean is at h / 2
            v, vdot = start[1], 2.0 * (v_after - start[1]) / h
        elif velocity == STATE:
            v, vdot = v_before, (v_after - v_before) / h
        else:
            v, vdot = (v_before + v_after) / 2.0, (v_after - v_before) / h
        levels[k] = _read(built, reader, q, v, vdot, bodies)
    theta = np.unwrap(levels[:, 0, :, 2], axis=0)
    theta += 2.0 * math.pi * np.round((guesses - theta[0]) / (2.0 * math.pi))
    levels[:, 0, :, 2] = theta
    trajectory = Trajectory(np.asarray(times, dtype=float), bodies, levels[:, 0], levels[:, 1], levels[:, 2])
    return trajectory, steps
