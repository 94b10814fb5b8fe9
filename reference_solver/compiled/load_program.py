"""A scenario's force elements compiled into flat arrays for the dynamics kernel (compiled.rates), the
same elements reference_solver.dynamics.loads evaluates in Python: applied torques and forces,
translational and rotational spring-dampers. Gravity is a vector over the coordinates, passed
beside them. One row per element: an integer row (kind, the two bodies' first columns, -1 for the
ground, and the motion codes of its time functions) and a real row (local points, stiffness,
damping, free length or angle, and the motions' parameters)."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from reference_solver.compiled.constraint_rows import NotCompiled
from reference_solver.compiled.program import motion_code
from reference_solver.layout import Layout
from scenarios.forces import AppliedForce, AppliedTorque, Force, RotationalSpringDamper, SpringDamper
from scenarios.motions import Motion

TORQUE, FORCE, SPRING, ROTATIONAL = 1, 2, 3, 4
# Integer columns.
L_KIND, L_COL_I, L_COL_J, L_MOTION_1, L_MOTION_2 = range(5)
LOAD_INTS = 5
# Real columns.
R_U_I, R_U_J = 0, 2  # two each: local coordinates of the element's points
R_STIFFNESS, R_DAMPING, R_FREE = 4, 5, 6
R_MOTION_1, R_MOTION_2 = 7, 11  # four parameters each
LOAD_REALS = 15


class LoadProgram(NamedTuple):
    ints: np.ndarray  # (elements, LOAD_INTS)
    reals: np.ndarray  # (elements, LOAD_REALS)
    gravity: np.ndarray  # (n,): m g on each body's x and y


def _column(layout: Layout, body: str) -> int:
    col = layout.body_column(body)
    return -1 if col is None else col


def _motions(ints: np.ndarray, reals: np.ndarray, *motions: Motion) -> None:
    for (k_col, r_col), motion in zip(
        ((L_MOTION_1, R_MOTION_1), (L_MOTION_2, R_MOTION_2)), motions, strict=False
    ):
        ints[k_col], params = motion_code(motion)
        reals[r_col : r_col + len(params)] = params


def _element(layout: Layout, force: Force, ints: np.ndarray, reals: np.ndarray) -> None:
    """Fill one element's rows."""
    if isinstance(force, AppliedTorque):
        ints[:3] = TORQUE, _column(layout, force.body), _column(layout, force.reaction)
        _motions(ints, reals, force.torque)
    elif isinstance(force, AppliedForce):
        ints[:3] = FORCE, _column(layout, force.point.body), -1
        reals[R_U_I : R_U_I + 2] = force.point.local
        _motions(ints, reals, force.fx, force.fy)
    elif isinstance(force, SpringDamper):
        ints[:3] = SPRING, _column(layout, force.p_i.body), _column(layout, force.p_j.body)
        reals[R_U_I : R_U_I + 2], reals[R_U_J : R_U_J + 2] = force.p_i.local, force.p_j.local
        reals[R_STIFFNESS : R_FREE + 1] = force.stiffness, force.damping, force.free_length
    elif isinstance(force, RotationalSpringDamper):
        ints[:3] = ROTATIONAL, _column(layout, force.body_i), _column(layout, force.body_j)
        reals[R_STIFFNESS : R_FREE + 1] = force.stiffness, force.damping, force.free_angle
    else:
        raise NotCompiled(f"no compiled kernel for force element {type(force).__name__}")


def compile_loads(forces: tuple[Force, ...], layout: Layout, gravity: np.ndarray) -> LoadProgram:
    """The load program of `forces` (NotCompiled for an element or motion without a kernel);
    `gravity` the generalized gravity force (dynamics.loads.Loads.gravity)."""
    ints = np.zeros((len(forces), LOAD_INTS), np.int64)
    reals = np.zeros((len(forces), LOAD_REALS))
    for k, force in enumerate(forces):
        _element(layout, force, ints[k], reals[k])
    return LoadProgram(ints, reals, np.ascontiguousarray(gravity, dtype=float))
