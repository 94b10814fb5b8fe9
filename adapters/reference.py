"""The native textbook solver presented as one more engine, so the runner treats it like the others.

Kinematic scenarios: its one knob is the Newton-Raphson tolerance (on both |dq| and |C|, relative to
the scenario's characteristic length); its sweep traces the native solver's own work-precision
curve. `inverse_dynamics=1` adds the drivers' forces, the joints' reactions and the energies as
extra columns. Dynamic scenarios: modes DOP853 and Radau (coordinate partitioning), knob `rtol`.
"""

from __future__ import annotations

from dataclasses import dataclass
from importlib.metadata import PackageNotFoundError
from importlib.metadata import version as package_version

import numpy as np

from adapters.base import Adapter, EngineFailure, Setting, Singular
from reference_solver import SingularConfigurationError, SolverError, analyse
from reference_solver.dynamics import inverse_dynamics, simulate
from reference_solver.dynamics.forward import METHODS
from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory

TOLERANCES = (1e-4, 1e-6, 1e-8, 1e-10, 1e-12)
RTOLS = (1e-6, 1e-8, 1e-10, 1e-12)


@dataclass(frozen=True)
class ReferenceModel:
    scenario: Scenario
    tolerance: float
    method: str = "newton"
    inverse: bool = False


class ReferenceAdapter(Adapter):
    name = "reference"
    dynamics = True

    def version(self) -> str:
        try:
            return package_version("mbxval")
        except PackageNotFoundError:
            return "unknown"

    def default_setting(self, scenario: Scenario) -> Setting:
        if scenario.analysis == "dynamic":
            return Setting.of("DOP853", rtol=1e-12)
        return Setting.of("newton", tolerance=1e-12)

    def sweep(self, scenario: Scenario) -> list[Setting]:
        if scenario.analysis == "dynamic":
            return [Setting.of("DOP853", rtol=tol) for tol in RTOLS]
        return [Setting.of("newton", tolerance=tol) for tol in TOLERANCES]

    def build(self, scenario: Scenario, setting: Setting) -> ReferenceModel:
        modes = METHODS if scenario.analysis == "dynamic" else ("newton",)
        if setting.mode not in modes:
            raise EngineFailure(
                f"unknown mode '{setting.mode}' for the reference solver on {scenario.name} "
                f"(known: {', '.join(modes)})"
            )
        key = "rtol" if scenario.analysis == "dynamic" else "tolerance"
        tolerance = float(setting.get(key, 1e-12))
        if not tolerance > 0:
            raise EngineFailure(f"{key} must be positive, got {tolerance}")
        inverse = bool(int(setting.get("inverse_dynamics", 0)))
        return ReferenceModel(scenario, tolerance, setting.mode, inverse)

    def simulate(self, model: ReferenceModel, times: np.ndarray) -> Trajectory:
        try:
            if model.scenario.analysis == "dynamic":
                dynamic = simulate(model.scenario, times, model.tolerance, model.method)
                self.count_steps(dynamic.evaluations)
                return dynamic.trajectory()
            analysis = analyse(model.scenario, times, model.tolerance)
            trajectory = analysis.trajectory()
            if model.inverse:
                trajectory.extras.update(inverse_dynamics(model.scenario, analysis))
        except SingularConfigurationError as error:
            raise Singular(str(error), error.time) from error
        except SolverError as error:
            raise EngineFailure(str(error), error.time) from error
        self.count_steps(int(analysis.iterations.sum()))
        return trajectory
