"""Drake's Simulator over the output grid, read into the canonical trajectory.

SAP's discrete step is q(n+1) = q(n) + h v(n+1): the plant's velocity after a step is the mean over
that step, the derivative at its midpoint. The trajectory's velocity at an output time t is therefore
read (by default) as the mean of the two step velocities around it, the central difference
(q(t + h) - q(t - h)) / 2h of Drake's own positions, and its acceleration as their difference over h,
also centred on t; with `velocity = "state"` the plant's state velocity is given as it is (the
midpoint value of the step before t, what a user reading the state gets). A driven march starts
RUN_IN steps before the first output; a free one at the first output, from the scenario's state.
Body rates come from the plant's spatial velocities and accelerations at those generalized values
(CalcSpatialAccelerationsFromVdot).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from pydrake.systems.analysis import Simulator  # not pydrake.all, which imports matplotlib

from adapters.drake.forces import ForceReader
from adapters.drake.model import Diagram
from adapters.lattice import check_grid, lattice_point
from scenarios.trajectory import Trajectory

CENTRAL, STATE = "central", "state"
RUN_IN = 10
"""Steps Drake runs before the first output, from a start assembled that much earlier: SAP's
constraints settle over the first few steps from an assembled state (the acceleration then is off by
up to 2 L omega^2), so every output is on Drake's settled march."""


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
    start: tuple[float, np.ndarray, np.ndarray],
    times: np.ndarray,
    bodies: tuple[str, ...],
    velocity: str,
    guesses: np.ndarray,
    forces: ForceReader | None = None,
) -> tuple[Trajectory, int]:
    """The trajectory on `times` from the consistent `start` (t, q, v) at or before times[0], and
    the steps taken; with `forces`, their columns as extras (the mean of the steps either side of
    each output, as the velocities). Every output time must be on the plant's step lattice
    (adapters.lattice)."""
    check_grid(times, float(times[0]))
    h = built.dt
    t_start = start[0]
    if t_start > float(times[0]) + 1e-12 * h:
        raise ValueError(f"the Drake run starts at t = {t_start:g}, after the first output")
    if any(lattice_point(t_start, float(t), h)[1] != 0.0 for t in times):
        raise ValueError(f"the output grid is not on Drake's step lattice (step {h:.6g} s)")
    simulator = Simulator(built.diagram)  # its clock reads t - t_start (model.build_diagram)
    root = simulator.get_mutable_context()
    plant_context = built.plant.GetMyMutableContextFromRoot(root)
    built.plant.SetPositions(plant_context, start[1])
    built.plant.SetVelocities(plant_context, start[2])
    simulator.Initialize()
    reader = built.plant.CreateDefaultContext()
    levels = np.zeros((len(times), 3, len(bodies), 3))
    found = np.zeros((len(times), len(forces.columns) if forces else 0))
    steps = 0
    for k, t in enumerate(times):
        m, _ = lattice_point(t_start, float(t), h)
        if m == 0:  # the start itself: AdvanceTo(0) takes the first step (Drake's update at 0)
            q, v_before = start[1], start[2]
            simulator.AdvanceTo(0.0)
            v_after = built.plant.GetVelocities(plant_context).copy()
            v = v_before  # the start's own rates, not a step's mean
            if forces:
                found[k] = forces.read(plant_context)  # the first step's: none before the start
        else:
            simulator.AdvanceTo(m * h)
            q = built.plant.GetPositions(plant_context).copy()
            v_before = built.plant.GetVelocities(plant_context).copy()
            before = forces.read(plant_context) if forces else None
            simulator.AdvanceTo((m + 1) * h)
            v_after = built.plant.GetVelocities(plant_context).copy()
            v = v_before if velocity == STATE else (v_before + v_after) / 2.0
            if forces and before is not None:
                found[k] = (before + forces.read(plant_context)) / 2.0
        steps = m + 1
        levels[k] = _read(built, reader, q, v, (v_after - v_before) / h, bodies)
    theta = np.unwrap(levels[:, 0, :, 2], axis=0)
    theta += 2.0 * math.pi * np.round((guesses - theta[0]) / (2.0 * math.pi))
    levels[:, 0, :, 2] = theta
    extras = {c: found[:, i].copy() for i, c in enumerate(forces.columns)} if forces else {}
    trajectory = Trajectory(
        np.asarray(times, dtype=float), bodies, levels[:, 0], levels[:, 1], levels[:, 2], extras
    )
    return trajectory, steps
