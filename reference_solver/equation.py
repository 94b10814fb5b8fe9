"""The base of every constraint's equations in the stacked system.

A subclass sets, in its __init__ after calling the base's:
    labels   one name per constraint row (one scalar equation of C), e.g. ("A.x", "A.y")
    powers   the power of length of each constraint row's units (0 angle, 1 length, 2 area): they
             are divided by L**power when tolerances and conditioning are judged
and implements constraint_rows(q, qd, t) -> tuple of ConstraintRow (value, Jacobian over `columns`,
Q_d). A driver also overrides c_t(t). Everything else (gathering poses, building points) is here.
"Constraint row" is the name of one equation of C everywhere (never a bare "row", which is a
results table's).
"""

from __future__ import annotations

import numpy as np

from reference_solver.kinematic_vectors import ConstraintRow, KinematicVector, body_point, body_vector
from reference_solver.layout import Layout
from scenarios.bodies import GROUND, Point


class Equation:
    labels: tuple[str, ...] = ()
    powers: tuple[int, ...] = ()

    def __init__(self, name: str, layout: Layout, bodies: tuple[str, ...], contact: str | None = None):
        self.name = name
        self.layout = layout
        moving = tuple(dict.fromkeys(b for b in bodies if b != GROUND))
        self._local = {b: 3 * k for k, b in enumerate(moving)}
        columns = [layout.body_column(b) for b in moving]
        cols = [c + k for c in columns if c is not None for k in range(3)]
        self.phi_local: int | None = None
        if contact is not None:
            self.phi_local = len(cols)
            cols.append(layout.phi_column(contact))
        self.columns = np.array(cols, dtype=int)
        self.width = len(cols)

    @property
    def size(self) -> int:
        return len(self.labels)

    def constraint_rows(self, q: np.ndarray, qd: np.ndarray, t: float) -> tuple[ConstraintRow, ...]:
        raise NotImplementedError

    def c_t(self, t: float) -> np.ndarray:
        """Partial derivative of the constraint rows in time; zero for a time-independent constraint."""
        return np.zeros(self.size)

    # --- building blocks for subclasses ---------------------------------------------------------
    def local(self, body: str) -> int | None:
        """The body's first local column, None for the ground."""
        return None if body == GROUND else self._local[body]

    def state(self, q: np.ndarray, qd: np.ndarray, body: str) -> tuple[np.ndarray, np.ndarray]:
        """The body's pose and its rate (zeros for the ground)."""
        col = self.layout.body_column(body)
        if col is None:
            return np.zeros(3), np.zeros(3)
        return q[col : col + 3], qd[col : col + 3]

    def point(self, q: np.ndarray, qd: np.ndarray, p: Point) -> KinematicVector:
        pose, rate = self.state(q, qd, p.body)
        return body_point(np.asarray(p.local, dtype=float), pose, rate, self.local(p.body), self.width)

    def direction(
        self, q: np.ndarray, qd: np.ndarray, body: str, local: tuple[float, float]
    ) -> KinematicVector:
        pose, rate = self.state(q, qd, body)
        return body_vector(np.asarray(local, dtype=float), pose, rate, self.local(body), self.width)

    def linear_constraint_row(
        self, q: np.ndarray, terms: dict[tuple[str, int], float], constant: float
    ) -> ConstraintRow:
        """sum of coefficient * q[body, coordinate] - constant, over `terms`; ground terms vanish."""
        jac = np.zeros(self.width)
        value = -constant
        for (body, coordinate), coefficient in terms.items():
            col = self.layout.body_column(body)
            if col is None:
                continue
            value += coefficient * q[col + coordinate]
            jac[self._local[body] + coordinate] += coefficient
        return ConstraintRow(value, jac, 0.0)
