"""Generalized forces Q_e of gravity and the force elements, with their potential energy and power.

Each element adds into Q_e as forces at body points (F at local u_P on body i gives F on (x, y)
and (A_theta u_P)^T F on theta). Springs store potential energy; dampers dissipate c l_dot^2;
applied forces and torques do work at the rate F . v_P (or T omega). The three together are what
the energy balance of a run accounts for.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from reference_solver.kinematic_vectors import perp, rotation
from reference_solver.layout import Layout
from scenarios.bodies import Point
from scenarios.forces import AppliedForce, AppliedTorque, RotationalSpringDamper, SpringDamper
from scenarios.scenario import Scenario


@dataclass(frozen=True)
class LoadState:
    """Q_e at one state, with the potential energy, the power of applied loads and the power the
    dampers dissipate (>= 0)."""

    generalized: np.ndarray
    potential: float
    applied_power: float
    dissipation: float


class Loads:
    """Gravity and every force element of a scenario, evaluated together."""

    def __init__(self, scenario: Scenario, layout: Layout, mass: np.ndarray):
        self.layout = layout
        self.gravity = np.zeros(layout.size)
        for k in range(len(layout.bodies)):
            self.gravity[3 * k : 3 * k + 2] = mass[3 * k] * np.asarray(scenario.gravity, dtype=float)
        self.forces = scenario.forces

    def __call__(self, q: np.ndarray, qd: np.ndarray, t: float) -> LoadState:
        q_e = self.gravity.copy()
        potential = -float(self.gravity @ q)
        applied = 0.0
        dissipation = 0.0
        for force in self.forces:
            if isinstance(force, AppliedTorque):
                applied += self._torque(q_e, qd, force.body, force.reaction, force.torque.f(t))
            elif isinstance(force, AppliedForce):
                f = np.array([force.fx.f(t), force.fy.f(t)])
                _, v = self._point(q, qd, force.point)
                self._at_point(q_e, q, force.point, f)
                applied += float(f @ v)
            elif isinstance(force, SpringDamper):
                potential, dissipation = self._spring(q_e, q, qd, force, potential, dissipation)
            elif isinstance(force, RotationalSpringDamper):
                stretch = self._angle(q, force.body_j) - self._angle(q, force.body_i) - force.free_angle
                rate = self._angle(qd, force.body_j) - self._angle(qd, force.body_i)
                torque = force.stiffness * stretch + force.damping * rate
                self._torque(q_e, qd, force.body_i, force.body_j, torque)
                potential += 0.5 * force.stiffness * stretch**2
                dissipation += force.damping * rate**2
            else:
                raise TypeError(f"no generalized force for {type(force).__name__}")
        return LoadState(q_e, potential, applied, dissipation)

    # --- elements -------------------------------------------------------------------------------
    def _spring(
        self,
        q_e: np.ndarray,
        q: np.ndarray,
        qd: np.ndarray,
        force: SpringDamper,
        potential: float,
        dissipation: float,
    ) -> tuple[float, float]:
        r_i, v_i = self._point(q, qd, force.p_i)
        r_j, v_j = self._point(q, qd, force.p_j)
        d = r_j - r_i
        length = float(np.hypot(d[0], d[1]))
        u = d / length
        rate = float(u @ (v_j - v_i))
        tension = force.stiffness * (length - force.free_length) + force.damping * rate
        self._at_point(q_e, q, force.p_i, tension * u)
        self._at_point(q_e, q, force.p_j, -tension * u)
        potential += 0.5 * force.stiffness * (length - force.free_length) ** 2
        return potential, dissipation + force.damping * rate**2

    def _torque(self, q_e: np.ndarray, qd: np.ndarray, body: str, reaction: str, torque: float) -> float:
        """+torque on `body`, -torque on `reaction`; returns its power."""
        for name, sign in ((body, 1.0), (reaction, -1.0)):
            col = self.layout.body_column(name)
            if col is not None:
                q_e[col + 2] += sign * torque
        return torque * (self._angle(qd, body) - self._angle(qd, reaction))

    def _angle(self, q: np.ndarray, body: str) -> float:
        col = self.layout.body_column(body)
        return 0.0 if col is None else float(q[col + 2])

    def _point(self, q: np.ndarray, qd: np.ndarray, p: Point) -> tuple[np.ndarray, np.ndarray]:
        """Global position and velocity of a body point."""
        local = np.asarray(p.local, dtype=float)
        col = self.layout.body_column(p.body)
        if col is None:
            return local, np.zeros(2)
        au = rotation(q[col + 2]) @ local
        return q[col : col + 2] + au, qd[col : col + 2] + perp(au) * qd[col + 2]

    def _at_point(self, q_e: np.ndarray, q: np.ndarray, p: Point, f: np.ndarray) -> None:
        """Add a force f (global axes) acting at a body point."""
        col = self.layout.body_column(p.body)
        if col is None:
            return
        au = rotation(q[col + 2]) @ np.asarray(p.local, dtype=float)
        q_e[col : col + 2] += f
        q_e[col + 2] += float(perp(au) @ f)
