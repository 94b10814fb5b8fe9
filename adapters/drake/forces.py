"""Joint reactions read from Drake's plant, in the canonical force columns (reports.scoring.forces):
`<joint>.fx`, `<joint>.fy` the force the joint applies to its first moving body (p_i's body, else
p_j's), world axes.

The reactions are the plant's reaction-forces output (the spatial force on each tree joint's child
at the joint's child frame, in that frame). A discrete plant's outputs hold the last step's values:
the mean over that step. Like the velocities (adapters.drake.simulation), a force at an output time
is the mean of the steps on either side of it. A loop closed by a ball constraint reports no force
of its own in Drake, so only the tree's joints carry reactions. A prismatic joint's reaction is
normal to its axis: Drake's includes a drive's push along it, which is taken out.

The driving force (`<driver>.force`, the PD drive's net actuation, read the same way when
`with_driver`) is not given by default: it is first order in the step like the reactions, and the
work it adds up over a run misses the energy balance by 1 to 3 % at the default step, past the
self-check's limit (reports.scoring.self_check), which would mark accurate runs as drifted.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from pydrake.multibody.tree import PrismaticJoint

from adapters.drake.model import Diagram
from adapters.drake.tree import Plan
from scenarios.bodies import GROUND
from scenarios.joints import Ground, Prismatic, Revolute
from scenarios.scenario import Scenario


def _first_moving(joint: Ground | Prismatic | Revolute) -> str:
    if isinstance(joint, Ground):
        return joint.body
    return joint.p_i.body if joint.p_i.body != GROUND else joint.p_j.body


class ForceReader:
    """The force columns of a built plant and their values in a plant context."""

    def __init__(self, built: Diagram, plan: Plan, scenario: Scenario, with_driver: bool = False) -> None:
        named = {j.name: j for j in scenario.joints}
        self._plant = built.plant
        self._joints = []  # (Drake joint, sign: +1 where the child is the first moving body)
        columns = []
        for edge in plan.edges:
            joint = named[edge.name]
            assert isinstance(joint, Ground | Prismatic | Revolute)
            sign = 1.0 if _first_moving(joint) == edge.child else -1.0
            self._joints.append((built.plant.GetJointByName(edge.name), sign))
            columns += [f"{edge.name}.fx", f"{edge.name}.fy"]
        self._drive: tuple[Any, float] | None = None
        if with_driver and plan.driver is not None and built.drive_joint is not None:
            self._drive = (built.drive_joint, built.drive_map[0])
            columns.append(f"{plan.driver.name}.force")
        self.columns = tuple(columns)

    def read(self, context: Any) -> np.ndarray:
        """Every column's value from the plant's outputs in `context` (the last step's means)."""
        plant = self._plant
        reactions = plant.get_reaction_forces_output_port().Eval(context)
        values: list[float] = []
        for joint, sign in self._joints:
            on_child = reactions[int(joint.index())].translational()
            rotation = joint.frame_on_child().CalcRotationMatrixInWorld(context).matrix()
            force = rotation @ on_child
            if isinstance(joint, PrismaticJoint):  # the drive's push along the axis is no reaction
                axis = rotation @ np.asarray(joint.translation_axis())
                force = force - (force @ axis) * axis
            values += list(sign * force[:2])
        if self._drive is not None:
            _, a = self._drive
            effort = plant.get_net_actuation_output_port().Eval(context)
            values.append(float(effort[0]) / a)  # the plant's one actuator
        return np.array(values)
