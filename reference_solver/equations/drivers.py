"""Equations of the drivers. Each supplies C_t = -f'(t) and adds f''(t) to Q_d."""

from __future__ import annotations

import numpy as np

from reference_solver.equation import Equation
from reference_solver.kinematic_vectors import ConstraintRow, components
from reference_solver.layout import Layout
from scenarios.drivers import (
    AbsoluteDriver,
    PointPathDriver,
    RelativeDisplacementDriver,
    RelativeRotationDriver,
)
from scenarios.motions import Motion

COORDINATES = {"x": 0, "y": 1, "theta": 2}


def _driven(row: ConstraintRow, motion: Motion, t: float) -> ConstraintRow:
    """row - f(t), with C_tt = -f'' moved into Q_d."""
    return ConstraintRow(row.value - motion.f(t), row.jac, row.q_d + motion.ddf(t))


class AbsoluteDriverEquation(Equation):
    """q_k - f(t) = 0 for one coordinate of one body."""

    def __init__(self, driver: AbsoluteDriver, layout: Layout):
        super().__init__(driver.name, layout, (driver.body,))
        self.driver = driver
        self.coordinate = COORDINATES[driver.coordinate]
        self.labels = (f"{driver.name}.{driver.coordinate}",)
        self.powers = (0 if driver.coordinate == "theta" else 1,)

    def constraint_rows(self, q: np.ndarray, qd: np.ndarray, t: float) -> tuple[ConstraintRow, ...]:
        row = self.linear_constraint_row(q, {(self.driver.body, self.coordinate): 1.0}, 0.0)
        return (_driven(row, self.driver.motion, t),)

    def c_t(self, t: float) -> np.ndarray:
        return np.array([-self.driver.motion.df(t)])


class RelativeRotationDriverEquation(Equation):
    """theta_i - theta_j - f(t) = 0."""

    def __init__(self, driver: RelativeRotationDriver, layout: Layout):
        super().__init__(driver.name, layout, (driver.body_i, driver.body_j))
        self.driver = driver
        self.labels = (f"{driver.name}.theta",)
        self.powers = (0,)

    def constraint_rows(self, q: np.ndarray, qd: np.ndarray, t: float) -> tuple[ConstraintRow, ...]:
        d = self.driver
        row = self.linear_constraint_row(q, {(d.body_i, 2): 1.0, (d.body_j, 2): -1.0}, 0.0)
        return (_driven(row, d.motion, t),)

    def c_t(self, t: float) -> np.ndarray:
        return np.array([-self.driver.motion.df(t)])


class PointPathDriverEquation(Equation):
    """r^P - (fx(t), fy(t)) = 0."""

    def __init__(self, driver: PointPathDriver, layout: Layout):
        super().__init__(driver.name, layout, (driver.point.body,))
        self.driver = driver
        self.labels = (f"{driver.name}.x", f"{driver.name}.y")
        self.powers = (1, 1)

    def constraint_rows(self, q: np.ndarray, qd: np.ndarray, t: float) -> tuple[ConstraintRow, ...]:
        rx, ry = components(self.point(q, qd, self.driver.point))
        return _driven(rx, self.driver.motion_x, t), _driven(ry, self.driver.motion_y, t)

    def c_t(self, t: float) -> np.ndarray:
        return -np.array([self.driver.motion_x.df(t), self.driver.motion_y.df(t)])


class RelativeDisplacementDriverEquation(Equation):
    """r_i^P - r_j^P - (fx(t), fy(t)) = 0."""

    def __init__(self, driver: RelativeDisplacementDriver, layout: Layout):
        super().__init__(driver.name, layout, (driver.p_i.body, driver.p_j.body))
        self.driver = driver
        self.labels = (f"{driver.name}.x", f"{driver.name}.y")
        self.powers = (1, 1)

    def constraint_rows(self, q: np.ndarray, qd: np.ndarray, t: float) -> tuple[ConstraintRow, ...]:
        d = self.driver
        rx, ry = components(self.point(q, qd, d.p_i) - self.point(q, qd, d.p_j))
        return _driven(rx, d.motion_x, t), _driven(ry, d.motion_y, t)

    def c_t(self, t: float) -> np.ndarray:
        return -np.array([self.driver.motion_x.df(t), self.driver.motion_y.df(t)])
