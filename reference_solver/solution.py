"""The result of a kinematic analysis: the solution on the grid with each time point's diagnostics."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from reference_solver.layout import Layout
from scenarios.trajectory import Trajectory


@dataclass(frozen=True)
class Analysis:
    """The solution on the grid, with the diagnostics of every time point."""

    layout: Layout
    times: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    qdd: np.ndarray
    iterations: np.ndarray
    residual: np.ndarray
    rcond: np.ndarray

    def trajectory(self, bodies: Sequence[str] | None = None) -> Trajectory:
        """The canonical trajectory of `bodies` (default: all), with each contact's phi as an extra."""
        bodies = tuple(bodies or self.layout.bodies)
        index = [
            c
            for b in bodies
            for c in range(3 * self.layout.bodies.index(b), 3 * self.layout.bodies.index(b) + 3)
        ]
        shape = (len(self.times), len(bodies), 3)
        extras = {f"{c}.phi": self.q[:, self.layout.phi_column(c)].copy() for c in self.layout.contacts}
        return Trajectory(
            self.times.copy(),
            bodies,
            position=self.q[:, index].reshape(shape),
            velocity=self.qd[:, index].reshape(shape),
            acceleration=self.qdd[:, index].reshape(shape),
            extras=extras,
        )
