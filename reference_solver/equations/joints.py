"""Equations of the joints: ground, revolute, prismatic, revolute-revolute."""

from __future__ import annotations

import numpy as np

from reference_solver.equation import Equation
from reference_solver.kinematic_vectors import ConstraintRow, components, inner
from reference_solver.layout import Layout
from scenarios.geometry import unit
from scenarios.joints import Ground, Prismatic, Revolute, RevoluteRevolute


class GroundEquation(Equation):
    """q_i - q_i0 = 0."""

    def __init__(self, joint: Ground, layout: Layout):
        super().__init__(joint.name, layout, (joint.body,))
        self.joint = joint
        self.labels = tuple(f"{joint.name}.{c}" for c in ("x", "y", "theta"))
        self.powers = (1, 1, 0)

    def constraint_rows(self, q: np.ndarray, qd: np.ndarray, t: float) -> tuple[ConstraintRow, ...]:
        body = self.joint.body
        return tuple(self.linear_constraint_row(q, {(body, k): 1.0}, self.joint.pose[k]) for k in range(3))


class RevoluteEquation(Equation):
    """r_i^P - r_j^P = 0."""

    def __init__(self, joint: Revolute, layout: Layout):
        super().__init__(joint.name, layout, (joint.p_i.body, joint.p_j.body))
        self.joint = joint
        self.labels = (f"{joint.name}.x", f"{joint.name}.y")
        self.powers = (1, 1)

    def constraint_rows(self, q: np.ndarray, qd: np.ndarray, t: float) -> tuple[ConstraintRow, ...]:
        return components(self.point(q, qd, self.joint.p_i) - self.point(q, qd, self.joint.p_j))


class PrismaticEquation(Equation):
    """theta_i - theta_j - c = 0 and h_i . (r_i^P - r_j^P) = 0, h_i normal to the axis on body i."""

    def __init__(self, joint: Prismatic, layout: Layout):
        super().__init__(joint.name, layout, (joint.p_i.body, joint.p_j.body))
        self.joint = joint
        ax, ay = unit(joint.axis)
        self.normal = (-ay, ax)
        self.labels = (f"{joint.name}.angle", f"{joint.name}.normal")
        self.powers = (0, 1)

    def constraint_rows(self, q: np.ndarray, qd: np.ndarray, t: float) -> tuple[ConstraintRow, ...]:
        j = self.joint
        angle = self.linear_constraint_row(q, {(j.p_i.body, 2): 1.0, (j.p_j.body, 2): -1.0}, j.angle)
        h = self.direction(q, qd, j.p_i.body, self.normal)
        return angle, inner(h, self.point(q, qd, j.p_i) - self.point(q, qd, j.p_j))


class RevoluteRevoluteEquation(Equation):
    """(r_i^P - r_j^P) . (r_i^P - r_j^P) - L^2 = 0."""

    def __init__(self, joint: RevoluteRevolute, layout: Layout):
        super().__init__(joint.name, layout, (joint.p_i.body, joint.p_j.body))
        self.joint = joint
        self.labels = (f"{joint.name}.length",)
        self.powers = (2,)

    def constraint_rows(self, q: np.ndarray, qd: np.ndarray, t: float) -> tuple[ConstraintRow, ...]:
        d = self.point(q, qd, self.joint.p_i) - self.point(q, qd, self.joint.p_j)
        row = inner(d, d)
        return (ConstraintRow(row.value - self.joint.length**2, row.jac, row.q_d),)
