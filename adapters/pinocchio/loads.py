"""The scenario's applied loads as Pinocchio joint torques tau, as Pinocchio's users write them.

Gravity is not here: it is the model's own `gravity` (in the plane), which Pinocchio applies at
every body's centre of mass. Torques act through each body's angular Jacobian row, forces at a
point through the transpose of the point frame's Jacobian; a spring-damper's tension comes from
the placements and velocities of its two point frames (`oMf` and J v), a torsion spring's from the
bodies' angles and angular rates. Each load is a term of tau = sum J^T f.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import pinocchio as pin

from adapters.pinocchio.model import PinModel, frame_jacobian
from scenarios.bodies import GROUND
from scenarios.forces import AppliedForce, AppliedTorque, Force, RotationalSpringDamper, SpringDamper

Term = Callable[[float, np.ndarray, np.ndarray], np.ndarray]
"""One load's joint torques at (t, q, v), Pinocchio's kinematics at q already updated."""


class Loads:
    """tau(t, q, v) of a scenario's forces on a Pinocchio model; each force is resolved once into a
    term with its frame ids and Jacobian rows, so that an evaluation is Pinocchio's kinematics and a
    few products."""

    def __init__(self, pm: PinModel, forces: tuple[Force, ...]) -> None:
        self.pm = pm
        self.data = pm.model.createData()
        self.needs_points = any(isinstance(f, SpringDamper | AppliedForce) for f in forces)
        self.terms = [self._term(force) for force in forces]

    def angle_row(self, body: str) -> np.ndarray:
        return self.pm.zero_v if body == GROUND else self.pm.angle_row[body]

    def _jacobian(self, fid: int) -> np.ndarray:
        """The (2, nv) planar rows of a point frame's LOCAL_WORLD_ALIGNED Jacobian."""
        return frame_jacobian(self.pm.model, self.data, fid)[:2]

    def _term(self, force: Force) -> Term:
        if isinstance(force, AppliedTorque):
            row = self.angle_row(force.body) - self.angle_row(force.reaction)
            return lambda t, q, v: force.torque.f(t) * row
        if isinstance(force, AppliedForce):
            fid = self.pm.frame_id[force.point]
            return lambda t, q, v: self._jacobian(fid).T @ np.array([force.fx.f(t), force.fy.f(t)])
        if isinstance(force, SpringDamper):
            return self._spring(force)
        if isinstance(force, RotationalSpringDamper):
            return self._torsion(force)
        raise TypeError(f"no Pinocchio load for {type(force).__name__}")

    def generalized(self, t: float, q: np.ndarray, v: np.ndarray) -> np.ndarray:
        """The joint torques tau equivalent to every applied load at (t, q, v)."""
        if self.needs_points:
            pin.computeJointJacobians(self.pm.model, self.data, q)
            pin.updateFramePlacements(self.pm.model, self.data)
        tau = np.zeros(self.pm.model.nv)
        for term in self.terms:
            tau += term(t, q, v)
        return tau

    def _spring(self, spring: SpringDamper) -> Term:
        """Tension k (l - l0) + c l' pulls p_i towards p_j and p_j towards p_i."""
        fi, fj = self.pm.frame_id[spring.p_i], self.pm.frame_id[spring.p_j]
        k, c, free = spring.stiffness, spring.damping, spring.free_length
        placements = self.data.oMf

        def term(t: float, q: np.ndarray, v: np.ndarray) -> np.ndarray:
            relative = self._jacobian(fi) - self._jacobian(fj)
            gap = placements[fi].translation[:2] - placements[fj].translation[:2]
            length = math.hypot(gap[0], gap[1])
            if length == 0.0:
                raise ValueError(f"spring-damper '{spring.name}' has zero length: no line of action")
            unit = gap / length
            # gap' = relative v, so l' = unit . relative v
            tension = k * (length - free) + c * float(unit @ (relative @ v))
            return -tension * (relative.T @ unit)

        return term

    def _torsion(self, spring: RotationalSpringDamper) -> Term:
        """T = k (theta_j - theta_i - theta0) + c (omega_j - omega_i): +T on body i, -T on body j."""
        row = self.angle_row(spring.body_j) - self.angle_row(spring.body_i)
        offset = self.pm.angle(spring.body_j, self.pm.zero_v) - self.pm.angle(spring.body_i, self.pm.zero_v)
        k, c, free = spring.stiffness, spring.damping, spring.free_angle

        def term(t: float, q: np.ndarray, v: np.ndarray) -> np.ndarray:
            torque = k * (offset + float(row @ q) - free) + c * float(row @ v)
            return -torque * row

        return term
