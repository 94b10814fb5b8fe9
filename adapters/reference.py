"""The native textbook solver presented as one more engine, so the runner treats it like the others.

Its one knob is the Newton-Raphson tolerance (on both |dq| and |C|, relative to the scenario's
characteristic length); its sweep traces the native solver's own work-precision curve.
"""

from __future__ import annotations

from dataclasses import dataclass
from importlib.metadata import PackageNotFoundError
from importlib.metadata import version as package_version

import numpy as np

from adapters.base import Adapter, EngineFailure, Option, Setting, Singular
from adapters.modes import ENGINE, Mode
from reference_solver import SingularConfigurationError, SolverError, analyse
from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory

TOLERANCES = (1e-4, 1e-6, 1e-8, 1e-10, 1e-12)


@dataclass(frozen=True)
class ReferenceModel:
    scenario: Scenario
    tolerance: float


class ReferenceAdapter(Adapter):
    name = "reference"
    measured = (
        Mode(
            "newton",
            ENGINE,
            "the native textbook Newton loop at each grid time, velocities and accelerations from "
            "its own linear solves",
        ),
    )
    modes = ("newton",)
    options = (Option("tolerance", float, 0.0, 0.1, low_open=True, help="Newton tolerance, scaled units"),)

    def version(self) -> str:
        try:
            return package_version("mbxval")
        except PackageNotFoundError:
            return "unknown"

    def default_setting(self, scenario: Scenario) -> Setting:
        return Setting.of("newton", tolerance=1e-12)

    def sweep(self, scenario: Scenario) -> list[Setting]:
        return [Setting.of("newton", tolerance=tol) for tol in TOLERANCES]

    def build(self, scenario: Scenario, setting: Setting) -> ReferenceModel:
        if setting.mode != "newton":
            raise EngineFailure(f"unknown mode '{setting.mode}' for the reference solver (known: newton)")
        tolerance = float(setting.get("tolerance", 1e-12))
        if not tolerance > 0:
            raise EngineFailure(f"tolerance must be positive, got {tolerance}")
        return ReferenceModel(scenario, tolerance)

    def simulate(self, model: ReferenceModel, times: np.ndarray) -> Trajectory:
        try:
            analysis = analyse(model.scenario, times, model.tolerance)
        except SingularConfigurationError as error:
            raise Singular(str(error), error.time) from error
        except SolverError as error:
            raise EngineFailure(str(error), error.time) from error
        self.count_steps(int(analysis.iterations.sum()))
        return analysis.trajectory()
