"""The smallest fake engine for timing tests: one mode, no options, the scenario itself as its model,
and a trajectory of zeros on whatever grid it is given. Subclasses say what a simulate call spends
(a fake clock, a sleep) and record what they were given; the runner and timing are what they test
(a fake is fine there), never an engine's numbers."""

from __future__ import annotations

import numpy as np

from adapters.base import Adapter, Setting
from scenarios import Scenario, Trajectory


class GridAdapter(Adapter):
    """Version "0", mode `good`, the scenario as its model; `zeros` is the trajectory it returns."""

    modes = ("good",)

    def version(self) -> str:
        return "0"

    def default_setting(self, scenario: Scenario) -> Setting:
        return Setting.of("good")

    def build(self, scenario: Scenario, setting: Setting) -> Scenario:
        return scenario

    @staticmethod
    def zeros(model: Scenario, times: np.ndarray) -> Trajectory:
        """Every output body at rest at the origin over `times`."""
        levels = np.zeros((len(times), len(model.output_bodies), 3))
        return Trajectory(np.asarray(times, dtype=float), model.output_bodies, levels, levels, levels)
