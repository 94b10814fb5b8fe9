"""The scenario's applied loads as Pinocchio joint torques tau, as Pinocchio's users write them.

Gravity is not here: it is the model's own `gravity` (in the plane), which Pinocchio applies at
every body's centre of mass. Torques act through each body's angular Jacobian row, forces at a
point through the transpose of the point frame's Jacobian; a spring-damper's tension comes from
the placements and velocities of its two point frames (`oMf` and J v), a torsion spring's from the
bodies' angles and angular rates. Each load is a term of tau = sum J^T f.
"""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin

from adapters.pinocchio.model import PinModel, frame_jacobian
from scenarios.bodies import GROUND, Point
from scenarios.forces import AppliedForce, AppliedTorque, Force, RotationalSpringDamper, SpringDamper


class Loads:
    """tau(t, q, v) of a scenario's forces on a Pinocchio model."""

    def __init__(self, pm: PinModel, forces: tuple[Force, ...]) -> None:
        self.pm, self.forces = pm, forces
        self.data = pm.model.createData()
        self.needs_points = any(isinstance(f, SpringDamper | AppliedForce) for f in forces)

    def angle_row(self, body: str) -> np.ndarray:
        return self.pm.zero_v if body == GROUND else self.pm.angle_row[body]

    def _point(self, point: Point, v: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Position, velocity and (2, nv) Jacobian of a point frame (kinematics already updated)."""
        fid = self.pm.frame_id[point]
        jac = frame_jacobian(self.pm.model, self.data, fid)[:2]
        return self.data.oMf[fid].translation[:2], jac @ v, jac

    def generalized(self, t: float, q: np.ndarray, v: np.ndarray) -> np.ndarray:
        """The joint torques tau equivalent to every applied load at (t, q, v)."""
        tau = np.zeros(self.pm.model.nv)
        if self.needs_points:
            model = self.pm.model
            pin.computeJointJacobians(model, self.data, q)
            pin.updateFramePlacements(model, self.data)
        for force in self.forces:
            if isinstance(force, AppliedTorque):
                torque = force.torque.f(t)
                tau += torque * (self.angle_row(force.body) - self.angle_row(force.reaction))
            elif isinstance(force, AppliedForce):
                _, _, jac = self._point(force.point, v)
                tau += jac.T @ np.array([force.fx.f(t), force.fy.f(t)])
            elif isinstance(force, SpringDamper):
                tau += self._spring(force, v)
            elif isinstance(force, RotationalSpringDamper):
                rows = self.angle_row(force.body_i), self.angle_row(force.body_j)
                twist = self.pm.angle(force.body_j, q) - self.pm.angle(force.body_i, q) - force.free_angle
                torque = force.stiffness * twist + force.damping * float((rows[1] - rows[0]) @ v)
                tau += torque * (rows[0] - rows[1])
            else:
                raise TypeError(f"no Pinocchio load for {type(force).__name__}")
        return tau

    def _spring(self, spring: SpringDamper, v: np.ndarray) -> np.ndarray:
        """Tension k (l - l0) + c l' pulls p_i towards p_j and p_j towards p_i."""
        (xi, vi, ji), (xj, vj, jj) = self._point(spring.p_i, v), self._point(spring.p_j, v)
        gap = xj - xi
        length = math.hypot(gap[0], gap[1])
        if length == 0.0:
            raise ValueError(
                f"spring-damper '{spring.name}' has zero length: its line of action is undefined"
            )
        unit = gap / length
        tension = spring.stiffness * (length - spring.free_length) + spring.damping * float(unit @ (vj - vi))
        return tension * ((ji - jj).T @ unit)
