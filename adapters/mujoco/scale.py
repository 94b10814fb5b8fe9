"""What the MuJoCo model sizes by the mechanism rather than in absolute SI units.

MuJoCo's numbers are absolute: a tolerance of 1e-13 is 1e-13 m on a 1e-4 m linkage and on a
1e3 m one alike, and a clock of armature 1e9 is a flywheel beside the one and a feather beside the
other. So, as a MuJoCo user would when modelling a mechanism far from the metre scale:
- residual tolerances of the assembly are per constraint row, in the row's own units: a row's
  natural size is its Jacobian times the size of each dof (1 rad for a hinge, the mechanism's
  extent for a slide), so a loop closure is converged relative to the mechanism's size and a drive
  on an angle absolutely;
- contact margins and cam geometry are sized by the characteristic length;
- each clock's armature is CLOCK_RATIO times the inertia it drives (the mechanism's kinetic energy
  at a unit clock rate, at the assembled start), so the clock is as undisturbed, and the model as
  well conditioned, at every scale.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mujoco
import numpy as np

from scenarios.scenario import Scenario

CLOCK_RATIO = 1.0e11
"""Clock armature over the inertia it drives, at least (1e10 kg m^2 on the nominal slider-crank)."""
RELATIVE_TOLERANCE = 1e-13
"""Assembly residual per row, relative to the row's natural size."""


@dataclass(frozen=True)
class Scale:
    """`length`: the characteristic length, which sizes margins and geometry; `extent`: the largest
    coordinate of the mechanism (at least `length`), the size of position round-off."""

    length: float
    extent: float


def scale_of(scenario: Scenario) -> Scale:
    length = float(scenario.characteristic_length)
    reach = [abs(v) for b in scenario.bodies for v in (b.guess[0], b.guess[1], b.length)]
    return Scale(length, max([length, *reach]))


def dof_sizes(m: mujoco.MjModel, scale: Scale) -> np.ndarray:
    """Per dof, the size of a typical motion: 1 rad for a hinge, the extent for a slide."""
    slide = m.jnt_type[m.dof_jntid] == mujoco.mjtJoint.mjJNT_SLIDE
    return np.where(slide, scale.extent, 1.0)


def row_tolerances(jac: np.ndarray, sizes: np.ndarray) -> np.ndarray:
    """Residual tolerance per constraint row (rows x dofs Jacobian)."""
    natural = np.abs(jac * sizes[None, :]).max(axis=1, initial=0.0)
    return RELATIVE_TOLERANCE * np.where(natural > 0.0, natural, 1.0)


def clock_armature(m: mujoco.MjModel, d: mujoco.MjData, qvel: np.ndarray, clock_dofs: list[int]) -> float:
    """CLOCK_RATIO times the inertia a clock drives: twice the kinetic energy of the mechanism (the
    clocks left out) at `qvel`, the velocities of a unit clock rate, with d's mass matrix; rounded
    up to a power of ten (0 if the clock drives nothing)."""
    moving = np.array(qvel, dtype=float)
    moving[clock_dofs] = 0.0
    momentum = np.empty(m.nv)
    mujoco.mj_mulM(m, d, momentum, moving)
    inertia = CLOCK_RATIO * float(moving @ momentum)
    return 10.0 ** math.ceil(math.log10(inertia)) if inertia > 0.0 else 0.0
