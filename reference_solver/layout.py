"""Where each unknown lives in the solution vector, and the scales that make tolerances relative.

Moving bodies come first, three coordinates each (x, y, theta), in the scenario's order; then one
profile parameter phi per cam contact. The ground is not in the vector: its frame is the global frame.
Lengths are measured in units of the scenario's characteristic length L, so that tolerances and the
singularity test behave the same for a 0.1 mm and a 1 km mechanism.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from scenarios.bodies import GROUND
from scenarios.scenario import Scenario


@dataclass(frozen=True)
class Layout:
    bodies: tuple[str, ...]
    contacts: tuple[str, ...]
    length_scale: float

    @classmethod
    def of(cls, scenario: Scenario) -> Layout:
        return cls(scenario.body_names, tuple(c.name for c in scenario.cams), scenario.characteristic_length)

    @property
    def size(self) -> int:
        return 3 * len(self.bodies) + len(self.contacts)

    def body_column(self, body: str) -> int | None:
        """First column of the body's coordinates, None for the ground."""
        if body == GROUND:
            return None
        try:
            return 3 * self.bodies.index(body)
        except ValueError:
            raise KeyError(f"unknown body '{body}'") from None

    def phi_column(self, contact: str) -> int:
        return 3 * len(self.bodies) + self.contacts.index(contact)

    def column_scales(self) -> np.ndarray:
        """L for x and y columns, 1 for angles and profile parameters."""
        scales = np.ones(self.size)
        for k in range(len(self.bodies)):
            scales[3 * k : 3 * k + 2] = self.length_scale
        return scales

    def initial_guess(self, scenario: Scenario) -> np.ndarray:
        q = np.zeros(self.size)
        for k, body in enumerate(scenario.bodies):
            q[3 * k : 3 * k + 3] = body.guess
        for cam in scenario.cams:
            q[self.phi_column(cam.name)] = cam.phi_guess
        return q
