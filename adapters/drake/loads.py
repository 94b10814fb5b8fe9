"""The free-dynamics forces in Drake: spring-dampers as the plant's LinearSpringDamper elements,
applied torques and forces as externally applied spatial forces from a small source system (Drake's
discrete plant samples them at the start of each step), and gravity as the plant's field.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.multibody.math import SpatialForce
from pydrake.multibody.plant import ExternallyAppliedSpatialForce, MultibodyPlant
from pydrake.multibody.tree import LinearSpringDamper
from pydrake.systems.framework import LeafSystem

from scenarios.bodies import GROUND
from scenarios.forces import AppliedForce, AppliedTorque, SpringDamper


def add_springs(plant: MultibodyPlant, bodies: dict[str, Any], springs: tuple[SpringDamper, ...]) -> None:
    """Each spring-damper as a LinearSpringDamper between its two points (before Finalize)."""
    for spring in springs:
        plant.AddForceElement(
            LinearSpringDamper(
                bodies[spring.p_i.body],
                [*spring.p_i.local, 0.0],
                bodies[spring.p_j.body],
                [*spring.p_j.local, 0.0],
                spring.free_length,
                spring.stiffness,
                spring.damping,
            )
        )


class Loads(LeafSystem):  # type: ignore[misc]  # pydrake has no type information
    """The applied loads at the simulator's time plus `t_start` (the scenario's time at the
    simulator's 0), as the list of spatial forces the plant's applied-force input takes."""

    def __init__(
        self, bodies: dict[str, Any], loads: tuple[AppliedTorque | AppliedForce, ...], t_start: float
    ) -> None:
        super().__init__()
        self._bodies, self._loads, self._t_start = bodies, loads, t_start
        self.DeclareAbstractOutputPort(
            "applied_spatial_force",
            lambda: AbstractValue.Make([ExternallyAppliedSpatialForce()]),
            self._output,
        )

    def forces(self, t: float) -> list[ExternallyAppliedSpatialForce]:
        """The spatial forces at scenario time `t`: a torque on its body and minus it on the body it
        reacts on, a force at its point; nothing on the ground."""
        out = []
        for load in self._loads:
            if isinstance(load, AppliedTorque):
                torque = float(load.torque.f(t))
                for body, sign in ((load.body, 1.0), (load.reaction, -1.0)):
                    if body != GROUND:
                        out.append(self._applied(body, np.zeros(3), [0.0, 0.0, sign * torque], np.zeros(3)))
            elif load.point.body != GROUND:
                force = [float(load.fx.f(t)), float(load.fy.f(t)), 0.0]
                out.append(self._applied(load.point.body, [*load.point.local, 0.0], np.zeros(3), force))
        return out

    def _applied(self, body: str, point: Any, torque: Any, force: Any) -> ExternallyAppliedSpatialForce:
        applied = ExternallyAppliedSpatialForce()
        applied.body_index = self._bodies[body].index()
        applied.p_BoBq_B = np.asarray(point, dtype=float)
        applied.F_Bq_W = SpatialForce(np.asarray(torque, dtype=float), np.asarray(force, dtype=float))
        return applied

    def _output(self, context: Any, output: Any) -> None:
        output.set_value(self.forces(context.get_time() + self._t_start))
