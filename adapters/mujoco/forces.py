"""Driving forces and joint reactions read from MuJoCo's own constraint solution.

A driver is an equality tying its coordinate (affine in the tree joints) to a clock: the force it
applies along that coordinate is the part of J^T efc_force of its rows on the driven joints,
projected on the coordinate's gradient. A revolute or prismatic joint of the tree transmits
cfrc_int, the force the parent body applies on the child (after mj_rnePostConstraint, gravity and
every other constraint included); a prismatic's force along its axis is its coordinate's load,
not its reaction, and is taken out. A revolute closing a loop is a `connect`: its efc_force is the
force on the first site's body. Reactions are the force on the joint's first moving body in world
axes, the native solver's convention (reference_solver.dynamics.augmented.constraint_outputs).
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np

from adapters.mujoco.kinematics import EQUALITY
from adapters.mujoco.laws import Law
from adapters.mujoco.tree import Tree
from scenarios.bodies import GROUND
from scenarios.joints import Prismatic, Revolute
from scenarios.scenario import Scenario


@dataclass(frozen=True)
class DriverForce:
    """One driver's equality and the weights that project its generalized force on its coordinate:
    the coordinate's gradient over the model's dofs, divided by its squared norm."""

    name: str
    equality: int
    weights: np.ndarray


@dataclass(frozen=True)
class Reaction:
    """One joint's reaction: from the child's cfrc_int (tree joint, `slide` the joint whose axis
    is removed, -1 for a hinge) or a loop's connect equality (`equality` >= 0); `sign` turns it into
    the force on the scenario joint's first moving body."""

    name: str
    body: int
    equality: int
    slide: int
    sign: float


@dataclass(frozen=True)
class ForceMap:
    """Where each driver's force and each joint's reaction is in MuJoCo's data."""

    drivers: tuple[DriverForce, ...]
    reactions: tuple[Reaction, ...]

    def columns(self) -> list[str]:
        """The canonical trajectory columns this map fills, in `read` order."""
        names = [f"{d.name}.force" for d in self.drivers]
        for r in self.reactions:
            names += [f"{r.name}.fx", f"{r.name}.fy"]
        return names

    def only(self, names: set[str]) -> ForceMap:
        """The map restricted to the named drivers and joints (a model's own extra joints left out)."""
        return ForceMap(
            tuple(d for d in self.drivers if d.name in names),
            tuple(r for r in self.reactions if r.name in names),
        )

    def read(self, m: mujoco.MjModel, d: mujoco.MjData) -> np.ndarray:
        """The columns' values at d's computed state (mj_forward and mj_rnePostConstraint done)."""
        values = [_driver_force(m, d, driver) for driver in self.drivers]
        for reaction in self.reactions:
            values += list(_reaction(m, d, reaction))
        return np.array(values, dtype=float)


def force_map(scenario: Scenario, tree: Tree, laws: list[Law], m: mujoco.MjModel) -> ForceMap:
    """The map for a compiled model of `scenario` built on `tree` with `laws`."""
    drivers = []
    names = {d.name for d in scenario.drivers}
    for law in laws:
        if law.name not in names:
            continue
        gradient = np.zeros(m.nv)
        clock = law.clock.joint if law.clock else ""
        for dof_joint, coef in law.form.coefs.items():
            if dof_joint != clock:
                gradient[m.jnt_dofadr[m.joint(dof_joint).id]] += coef
        equality = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_EQUALITY, law.name)
        drivers.append(DriverForce(law.name, equality, gradient / (gradient @ gradient)))
    loops = {loop.name for loop in tree.closures}
    tree_joints = {j.name: j for j in tree.joints}
    reactions = []
    for joint in scenario.joints:
        if not isinstance(joint, Revolute | Prismatic):
            continue
        moving = next(p.body for p in (joint.p_i, joint.p_j) if p.body != GROUND)
        if joint.name in loops:
            equality = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_EQUALITY, joint.name)
            sign = 1.0 if joint.p_i.body == moving else -1.0
            reactions.append(Reaction(joint.name, -1, equality, -1, sign))
        elif joint.name in tree_joints:
            child = tree_joints[joint.name].child
            body = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_BODY, child)
            slide = m.joint(joint.name).id if isinstance(joint, Prismatic) else -1
            reactions.append(Reaction(joint.name, body, -1, slide, 1.0 if child == moving else -1.0))
    return ForceMap(tuple(drivers), tuple(reactions))


def _equality_rows(d: mujoco.MjData, equality: int) -> np.ndarray:
    """The constraint rows of one equality in d's current constraint set."""
    return np.flatnonzero((d.efc_type == EQUALITY) & (d.efc_id == equality))


def _driver_force(m: mujoco.MjModel, d: mujoco.MjData, driver: DriverForce) -> float:
    rows = _equality_rows(d, driver.equality)
    generalized = d.efc_J.reshape(d.nefc, m.nv)[rows].T @ d.efc_force[rows]
    return float(generalized @ driver.weights)


def _reaction(m: mujoco.MjModel, d: mujoco.MjData, reaction: Reaction) -> np.ndarray:
    if reaction.equality >= 0:
        return reaction.sign * d.efc_force[_equality_rows(d, reaction.equality)][:2]
    force = d.cfrc_int[reaction.body][3:].copy()
    if reaction.slide >= 0:
        axis = d.xaxis[reaction.slide]
        force -= (force @ axis) * axis
    return reaction.sign * force[:2]
