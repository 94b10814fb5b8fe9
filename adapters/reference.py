"""The native textbook solver presented as one more engine, so the runner treats it like the others.

Kinematic scenarios (mode newton): its one knob is the Newton-Raphson tolerance (on both |dq| and
|C|, relative to the scenario's characteristic length); its ladder traces the native solver's own
work-precision curve. `inverse_dynamics=1` (the default where every body has mass and its dense
solves are within scenarios.limits' MAX_DENSE_ROWS; refused before the analysis where its work is
above the limits) adds the drivers' forces, the joints' reactions and the energies as extra
columns, judged against the independent force truth where the scenario has one
(reports.scoring.forces). Dynamic scenarios (modes DOP853 and Radau, coordinate partitioning): the
knob is the integrator's relative tolerance `rtol`; mode ali3p, the second native method (index-3
augmented Lagrangian with projections, which passes singular configurations), takes the step `dt`
instead, so that each native method can check the other. Through singular passages (a family's
`singular_passages`), where the partitioned method cannot be relied on, ALI3-P is the default, at
the settings rule's step.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from importlib.metadata import PackageNotFoundError
from importlib.metadata import version as package_version

import numpy as np

from adapters import NATIVE
from adapters.base import Adapter, EngineFailure, Option, Setting, Singular
from adapters.knobs import FIXED, NOT_APPLICABLE, SWEPT, Knob
from adapters.modes import ENGINE, Mode
from adapters.step_rule import rule_step
from reference_solver import SingularConfigurationError, SolverError, analyse
from reference_solver.dynamics.methods import ALI3P, ALI3P_STEP, METHODS
from scenarios import limits
from scenarios.limits import check_dense_rows, dense_admitted
from scenarios.registry import singular_passages
from scenarios.scenario import Scenario, ScenarioError
from scenarios.trajectory import Trajectory

TOLERANCES = (1e-4, 1e-6, 1e-8, 1e-10, 1e-12)
ALI3P_STEPS_PER_PERIOD = 1000.0
"""ALI3-P's steps per shortest period (adapters.step_rule), its default where the scenario passes
singular configurations: on IFToMM A02 B0's position and velocity to a few 1e-4 of the
specification's 1e-3 (docs/a02.md)."""
RTOLS = (1e-6, 1e-8, 1e-10, 1e-12)
KNOBS = (
    Knob(
        "mode",
        FIXED,
        "newton on driven scenes, DOP853 in free dynamics (ALI3-P through singular passages); Radau and "
        "ALI3-P are the native checks of DOP853, run on request",
    ),
    Knob(
        "tolerance",
        SWEPT,
        f"Newton's tolerance, {TOLERANCES[0]:g} to {TOLERANCES[-1]:g} (the default): the native curve on "
        "driven scenes",
    ),
    Knob(
        "rtol",
        SWEPT,
        f"the integrator's relative tolerance, {RTOLS[0]:g} to {RTOLS[-1]:g} (the default), in free dynamics",
    ),
    Knob(
        "dt",
        FIXED,
        f"ALI3-P's step, the rule's at {ALI3P_STEPS_PER_PERIOD:g} steps per shortest period; ALI3-P is "
        "the default only through singular passages (docs/a02.md), and its step is not swept",
    ),
    Knob("inverse_dynamics", NOT_APPLICABLE, "adds force and energy columns; the motion is the same"),
    Knob(
        "compiled", NOT_APPLICABLE, "the same right-hand side compiled or plain (a check of the compilation)"
    ),
)
"""The native solver's knobs (adapters.knobs)."""


@dataclass(frozen=True)
class ReferenceModel:
    scenario: Scenario
    tolerance: float
    mode: str = "newton"
    inverse: bool = False
    step: float | None = None
    compiled: bool = True


class ReferenceAdapter(Adapter):
    name = NATIVE
    colour = "#444444"
    rule = (
        "no fixed step: Newton's tolerance 1e-12 (kinematics), DOP853's rtol 1e-12 (dynamics), each "
        f"swept to its floor; through singular passages ALI3-P at 1/{ALI3P_STEPS_PER_PERIOD:g} of the "
        "shortest period"
    )
    measured = (
        Mode(
            "newton",
            ENGINE,
            "the native textbook Newton loop at each grid time, velocities and accelerations from "
            "its own linear solves",
        ),
        *(
            Mode(method, ENGINE, f"the native forward dynamics (index-1 ODE) integrated by SciPy's {method}")
            for method in METHODS
        ),
        Mode(
            ALI3P,
            ENGINE,
            "the native forward dynamics by the index-3 augmented Lagrangian with projections "
            "(trapezoidal rule at a fixed step)",
        ),
    )
    options = (
        Option("tolerance", float, 0.0, 0.1, low_open=True, help="Newton tolerance, scaled units"),
        Option("rtol", float, 0.0, 0.1, low_open=True, help="integrator relative tolerance (dynamics)"),
        Option("dt", float, 0.0, 1.0, low_open=True, unit="s", help="ALI3-P's largest step (dynamics)"),
        Option("inverse_dynamics", int, 0, 1, help="1: add driver forces, reactions and energies"),
        Option(
            "compiled",
            int,
            0,
            1,
            help="dynamics: 1 (default) the compiled right-hand side, 0 the plain one, which checks it",
        ),
    )
    knobs = KNOBS
    dynamics = True

    def version(self) -> str:
        try:
            return package_version("mbxval")
        except PackageNotFoundError:
            return "unknown"

    def default_setting(self, scenario: Scenario) -> Setting:
        if scenario.analysis == "dynamic":
            if singular_passages(scenario):
                return Setting.of(ALI3P, dt=rule_step(scenario, ALI3P_STEPS_PER_PERIOD))
            return Setting.of("DOP853", rtol=1e-12)
        bodies = scenario.bodies
        if all(body.mass > 0.0 for body in bodies) and dense_admitted(len(bodies)):
            return Setting.of("newton", tolerance=1e-12, inverse_dynamics=1)
        return Setting.of("newton", tolerance=1e-12)

    def default_reason(self, scenario: Scenario) -> str:
        why = singular_passages(scenario) if scenario.analysis == "dynamic" else ""
        if not why:
            return ""
        step = rule_step(scenario, ALI3P_STEPS_PER_PERIOD)
        return (
            f"ali3p by default, dt = {step:.3g} s (1/{ALI3P_STEPS_PER_PERIOD:g} of the shortest period): "
            f"{why}, which the partitioned method (DOP853, Radau) cannot be relied on to cross"
        )

    def ladder(self, scenario: Scenario) -> list[Setting]:
        if scenario.analysis == "dynamic":
            return [Setting.of("DOP853", rtol=tol) for tol in RTOLS]
        return [Setting.of("newton", tolerance=tol) for tol in TOLERANCES]

    def build(self, scenario: Scenario, setting: Setting) -> ReferenceModel:
        dynamic = scenario.analysis == "dynamic"
        if (setting.mode in (*METHODS, ALI3P)) != dynamic:
            known = ", ".join((*METHODS, ALI3P)) if dynamic else "newton"
            raise EngineFailure(f"mode '{setting.mode}' does not apply to {scenario.name} (known: {known})")
        tolerance = float(setting.get("rtol" if dynamic else "tolerance", 1e-12))
        step = float(setting.get("dt", ALI3P_STEP)) if setting.mode == ALI3P else None
        inverse, compiled = bool(setting.get("inverse_dynamics", 0)), bool(setting.get("compiled", 1))
        if inverse:  # a dense least-squares solve per grid point
            check_dense_rows(scenario.name, len(scenario.bodies))
        elif not dynamic:
            warnings.warn(_forceless_reason(scenario), stacklevel=2)
        return ReferenceModel(scenario, tolerance, setting.mode, inverse, step, compiled)

    def simulate(self, model: ReferenceModel, times: np.ndarray) -> Trajectory:
        try:
            if model.scenario.analysis == "dynamic":
                from reference_solver.dynamics import simulate  # on first use: scipy.integrate

                compiled = model.compiled or model.mode == ALI3P  # ALI3-P: compiled constraints either way
                dynamic = simulate(model.scenario, times, model.tolerance, model.mode, compiled, model.step)
                self.count_steps(dynamic.evaluations)
                return dynamic.trajectory()
            if model.inverse:
                _check_inverse_work(model.scenario, len(times))
            analysis = analyse(model.scenario, times, model.tolerance, compiled=None)
            trajectory = analysis.trajectory()
            if model.inverse:
                from reference_solver.dynamics.inverse import inverse_dynamics

                trajectory.extras.update(inverse_dynamics(model.scenario, analysis, compiled=None))
        except SingularConfigurationError as error:
            raise Singular(str(error), error.time) from error
        except SolverError as error:
            raise EngineFailure(str(error), error.time) from error
        self.count_steps(int(analysis.iterations.sum()))
        return trajectory


def _forceless_reason(scenario: Scenario) -> str:
    """Why a kinematic run without inverse dynamics gives no forces."""
    if not all(body.mass > 0.0 for body in scenario.bodies):
        return "forces not given: a body without mass has no inverse dynamics"
    if not dense_admitted(len(scenario.bodies)):
        return f"forces not given: {len(scenario.bodies)} bodies are past the dense solve's limit"
    return "forces not given: inverse_dynamics=0 (1 adds the drivers' forces and the joints' reactions)"


def _check_inverse_work(scenario: Scenario, points: int) -> None:
    """Refuse, before the analysis, inverse dynamics whose dense solves are above scenarios.limits."""
    try:
        limits.check_work(scenario.name, points, len(scenario.bodies), dense=True)
    except ScenarioError as error:
        raise EngineFailure(f"{error} (its forces; inverse_dynamics=0 solves the motion alone)") from None
