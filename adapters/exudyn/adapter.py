"""Exudyn adapter: the same absolute-coordinate formulation as the textbook, implemented
independently, solved by Exudyn's own DAE solvers.

Modes (one work-precision curve each):
    GA3          generalized-alpha on the index-3 constraints, spectral radius 0.9, full Newton,
                 fixed step: positions exact to Newton's tolerance, velocities and accelerations
                 O(dt^2) once its start-up transient has died out in a run-in of `run_in` steps
                 before the first output (kinematic scenes, adapters.exudyn.run_in; the default,
                 at the rule's step: adapters.step_rule, adapters.exudyn.settings)
    GA3-rho0.5   the same with spectral radius 0.5 (a shorter transient)
    GA3-modified GA3 with Exudyn's own modified Newton (the Jacobian kept over iterations and steps,
                 Exudyn's default; the other modes update it at every iteration)
    TR2          the trapezoidal rule (Newmark 1/4, 1/2) on index-2 constraints; positions drift O(dt^2)
    STATIC       Exudyn's static solver at each grid time, then velocity and acceleration solves on
                 Exudyn's own constraint Jacobian and velocity-level constraints (kinematic scenes)
    untuned      generalized-alpha with every setting at Exudyn's own default (spectral radius 0.9,
                 modified Newton on the residual at 1e-8, adaptive step reduction, its own initial
                 accelerations, no run-in) at the rule's step: what a new user's model gets
    RK44         Exudyn's explicit RK4: unsupported wherever a joint or driver is (Exudyn's explicit
                 integrators eliminate only coordinate constraints to the ground)
In free dynamics (scenarios whose analysis is "dynamic") gravity and the force elements are Exudyn's
loads and connectors (adapters.exudyn.loads), the start is the scenario's assembled state with
Exudyn's own initial accelerations (adapters.exudyn.initial_state, at build), and GA3, GA3-rho0.5
and TR2 integrate it (second order in the step); a system of more than SPARSE_ABOVE coordinates
uses Exudyn's sparse linear solver.
Options: `dt` (the step; the march takes the largest step at or below it that puts the outputs on
its steps, adapters.lattice.outputs_on_steps; only an uneven grid is interpolated, and the run
warns), `run_in` (steps of run-in before the first output; by default the transient's decay at
the mode's spectral radius on kinematic scenes, 0 in free dynamics), `rho` (overrides the mode's
spectral radius), `tol` (Newton's tolerance on its increment, per unit of coordinate size),
`mass_scale` (multiplies every mass and inertia; a kinematically driven result must not depend on
it), `cams` ('native' puts knife-edge and roller followers on a circular disc on Exudyn's distance
connector; 'user' sends every cam through the user-function connector).
Every run starts from a consistent state that Exudyn's static solver finds from the scenario's
rough guess (adapters.exudyn.assembly.assemble). Exudyn has no model file format (its models are Python
scripts), so there is no export.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

import exudyn as exu
import numpy as np

from adapters.base import Adapter, Option, Setting, Unsupported
from adapters.exudyn.assembly import States, assemble
from adapters.exudyn.initial_state import released_start
from adapters.exudyn.knobs import KNOBS
from adapters.exudyn.loads import FORCES
from adapters.exudyn.model import ExudynModel, ModelError, build_model
from adapters.exudyn.run_in import MAX_RUN_IN, run_in_start, run_in_steps
from adapters.exudyn.settings import STEPS_PER_PERIOD, rule_default, rule_ladder, rule_untuned
from adapters.exudyn.simulation import Plan, march, quiet, simulation_settings, trajectory, untuned_settings
from adapters.lattice import outputs_on_steps
from adapters.modes import ENGINE, Mode
from scenarios.cam_linkage import CAM_MODELS, default_cam_model, linkage_reason
from scenarios.cams import FlatFaceCam, KnifeEdgeCam, RollerCam
from scenarios.drivers import (
    AbsoluteDriver,
    PointPathDriver,
    RelativeDisplacementDriver,
    RelativeRotationDriver,
)
from scenarios.gears import GearPair, RackPinion
from scenarios.joints import Ground, Prismatic, Revolute, RevoluteRevolute
from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory

MODES: dict[str, tuple[str, float, float]] = {  # solver, spectral radius, Newton tolerance
    "GA3": ("GA", 0.9, 1e-12),
    "GA3-rho0.5": ("GA", 0.5, 1e-12),
    "GA3-modified": ("GA", 0.9, 1e-12),
    "TR2": ("TR2", 1.0, 1e-12),
    "STATIC": ("STATIC", 1.0, 1e-14),
    "RK44": ("RK44", 1.0, 1e-12),
    "untuned": ("GA", 0.9, 1e-8),
}
MODIFIED_NEWTON = ("GA3-modified", "untuned")
UNTUNED = "untuned"
"""The mode that runs Exudyn's own defaults."""
"""Modes that keep Exudyn's own modified Newton (its Jacobian reused over iterations and steps)."""
EXPLICIT_REASON = (
    "Exudyn's explicit integrators (RK44, DOPRI5, ...) refuse joint constraints: they eliminate only "
    "coordinate constraints to the ground, and this scenario has {what}"
)
CONSTRAINT_ROWS: dict[type, int] = {  # how many constraint rows each item adds
    Revolute: 2,
    Prismatic: 2,
    RevoluteRevolute: 1,
    Ground: 3,
    GearPair: 1,
    RackPinion: 1,
    KnifeEdgeCam: 2,
    RollerCam: 2,
    FlatFaceCam: 2,
    AbsoluteDriver: 1,
    RelativeRotationDriver: 1,
    PointPathDriver: 2,
    RelativeDisplacementDriver: 2,
}
OPTIONS = ("dt", "rho", "tol", "mass_scale", "cams", "cam_model", "run_in")
SPARSE_ABOVE = 100
"""Coordinates above which free dynamics uses Exudyn's sparse linear solver."""


@dataclass(frozen=True)
class ExudynRun:
    model: ExudynModel
    plan: Plan
    start: tuple[float, States] | None = None
    """(t0, state): the consistent start found at build time, outside the timed run."""


class ExudynAdapter(Adapter):
    name = "exudyn"
    colour = "#d62728"
    packages = ("exudyn",)
    dynamics = True
    rule = (
        f"GA3 (spectral radius 0.9, full Newton) at 1/{STEPS_PER_PERIOD} of the shortest period, "
        f"after a run-in of {run_in_steps(0.9)} steps on kinematic scenes"
    )
    measured = (
        Mode(
            "GA3",
            ENGINE,
            "Exudyn's generalized-alpha (index 3, spectral radius 0.9; after a run-in on kinematic scenes), "
            "all levels from its state",
        ),
        Mode(
            "GA3-rho0.5",
            ENGINE,
            "Exudyn's generalized-alpha (index 3, spectral radius 0.5), all levels from its state",
        ),
        Mode(
            "GA3-modified",
            ENGINE,
            "Exudyn's generalized-alpha (index 3, spectral radius 0.9) with its modified Newton, all levels "
            "from its state",
        ),
        Mode("TR2", ENGINE, "Exudyn's trapezoidal rule (index 2), all levels from its state"),
        Mode(
            UNTUNED,
            ENGINE,
            "Exudyn's generalized-alpha with all of Exudyn's default settings, all levels from its state",
        ),
        Mode(
            "RK44", ENGINE, "Exudyn's explicit RK4 (constraint-free scenes only), all levels from its state"
        ),
        Mode(
            "STATIC",
            ENGINE,
            "Exudyn's static solver at each grid time (positions)",
            (
                ("velocity", "adapter solve on Exudyn's constraint Jacobian"),
                ("acceleration", "adapter solve with finite differences of Exudyn's constraints"),
            ),
        ),
    )
    knobs = KNOBS
    options = (
        Option("dt", float, 0.0, 1.0, low_open=True, unit="s", help="integration step"),
        Option("rho", float, 0.0, 1.0, help="spectral radius of generalized-alpha"),
        Option("tol", float, 0.0, 1.0, low_open=True, help="Newton tolerance"),
        Option("run_in", int, 0, MAX_RUN_IN, help="generalized-alpha steps before the first output"),
        Option("cams", str, choices=("native", "user"), help="cam rows by native elements or user functions"),
        Option(
            "cam_model", str, choices=CAM_MODELS, help="disc cams as their equivalent linkage, or as contacts"
        ),
        Option("mass_scale", float, 0.0, 1e12, help="masses multiplied by this (0: massless)"),
    )

    def version(self) -> str:
        import exudyn

        return str(exudyn.__version__)

    def supports(self, scenario: Scenario) -> str | None:
        for item in (*scenario.joints, *scenario.drivers):
            if type(item) not in CONSTRAINT_ROWS:
                return f"no Exudyn element for {type(item).__name__} '{getattr(item, 'name', '?')}'"
            if isinstance(item, RevoluteRevolute) and not item.length > 0.0:
                return f"Exudyn's distance connector needs a positive length ('{item.name}': {item.length})"
        for force in scenario.forces:
            if not isinstance(force, FORCES):
                return f"no Exudyn element for {type(force).__name__} '{force.name}'"
        if scenario.analysis == "dynamic":
            return None
        count = sum(CONSTRAINT_ROWS[type(item)] for item in (*scenario.joints, *scenario.drivers))
        unknowns = 3 * len(scenario.bodies) + len(scenario.cams)
        if count != unknowns:
            return (
                f"not kinematically driven ({unknowns} coordinates, {count} constraint equations): "
                "Exudyn would integrate free dynamics that depend on the masses"
            )
        return None

    def default_setting(self, scenario: Scenario) -> Setting:
        setting = rule_default(scenario)
        return setting.replace(cam_model=default_cam_model(scenario)) if scenario.cams else setting

    def untuned_setting(self, scenario: Scenario) -> Setting:
        setting = rule_untuned(scenario)
        return setting.replace(cam_model=default_cam_model(scenario)) if scenario.cams else setting

    def ladder(self, scenario: Scenario) -> list[Setting]:
        """adapters.exudyn.settings' ladders (the explicit integrators refuse joints, see
        EXPLICIT_REASON)."""
        return rule_ladder(scenario)

    def build(self, scenario: Scenario, setting: Setting) -> ExudynRun:
        if setting.mode not in MODES:
            raise ValueError(f"unknown Exudyn mode '{setting.mode}'; known: {', '.join(MODES)}")
        unknown = [key for key, _ in setting.options if key not in OPTIONS]
        if unknown:
            raise ValueError(f"unknown Exudyn option(s) {', '.join(unknown)}; known: {', '.join(OPTIONS)}")
        solver, rho, tolerance = MODES[setting.mode]
        dynamic = scenario.analysis == "dynamic"
        rho = float(setting.get("rho", rho))
        untuned = setting.mode == UNTUNED
        runs_in = solver == "GA" and not dynamic and not untuned
        plan = Plan(
            solver=solver,
            dt=float(setting.get("dt", rule_default(scenario)["dt"])),
            rho=rho,
            tolerance=float(setting.get("tol", tolerance)),
            modified_newton=setting.mode in MODIFIED_NEWTON,
            run_in=int(setting.get("run_in", run_in_steps(rho) if runs_in else 0)),
            untuned=untuned,
        )
        if plan.run_in and (dynamic or solver != "GA"):
            raise ValueError("run_in applies to generalized-alpha on kinematically driven scenarios only")
        # the equivalent linkage is Exudyn's native distance connector (knife edge, roller) and its
        # exact native flat-face element; the contact is the user-function connector on the profile
        model_choice = str(setting.get("cam_model", default_cam_model(scenario)))
        if model_choice == "linkage" and linkage_reason(scenario):
            raise Unsupported(str(linkage_reason(scenario)))
        cams = str(setting.get("cams", "native" if model_choice == "linkage" else "user"))
        if not (plan.dt > 0.0 and plan.tolerance > 0.0 and 0.0 <= plan.rho <= 1.0):
            raise ValueError(f"invalid Exudyn setting {setting.label}")
        _check_dynamic_mode(scenario, plan, dynamic, float(setting.get("mass_scale", 1.0)))
        try:
            with quiet():
                model = build_model(scenario, float(setting.get("mass_scale", 1.0)), cams == "native")
        except ModelError as error:
            raise Unsupported(str(error)) from error
        times = np.asarray(scenario.times(), dtype=float)
        t0 = float(times[0])
        settings = _settings(model, replace(plan, untuned=False))  # every start is assembled alike
        with quiet():
            start = (released_start if dynamic else assemble)(model, t0, settings)
            if plan.run_in:  # the run-in's start for the scenario's own grid, outside the timed run
                run_in_start(model, settings, t0, outputs_on_steps(times, plan.dt), plan.run_in)
        return ExudynRun(model, plan, (t0, start))

    def simulate(self, model: ExudynRun, times: np.ndarray) -> Trajectory:
        grid = np.asarray(times, dtype=float)
        start = model.start[1] if model.start and model.start[0] == float(grid[0]) else None
        with quiet():
            states, steps = march(model.model, model.plan, grid, _settings(model.model, model.plan), start)
        self.count_steps(steps)
        return trajectory(model.model, grid, states)


def _check_dynamic_mode(scenario: Scenario, plan: Plan, dynamic: bool, mass_scale: float) -> None:
    """Unsupported for a mode that cannot run the scenario's analysis faithfully."""
    if plan.solver == "RK44":
        constrained = [*scenario.joints, *scenario.drivers]
        if constrained:
            what = f"{type(constrained[0]).__name__} '{getattr(constrained[0], 'name', '?')}'"
            raise Unsupported(EXPLICIT_REASON.format(what=what))
    if dynamic and plan.solver == "STATIC":
        raise Unsupported("Exudyn's static solver finds equilibria; free dynamics needs an integrator")
    if dynamic and mass_scale != 1.0:
        raise ValueError("mass_scale applies to kinematically driven scenarios only")


def _settings(model: ExudynModel, plan: Plan) -> Any:
    """Exudyn's settings; Newton's tolerance is on increments: relative to the coordinates' size.
    A large system integrates with Exudyn's sparse linear solver, as its users set it (on the
    81-body chain 45 times faster than the dense default; the same on small systems)."""
    if plan.untuned:
        return untuned_settings()
    size = max(1.0, float(np.max(np.abs(model.guess), initial=0.0)))
    settings = simulation_settings(plan.tolerance * size)
    settings.timeIntegration.newton.useModifiedNewton = plan.modified_newton
    if model.scenario.analysis == "dynamic" and len(model.guess) > SPARSE_ABOVE:
        settings.linearSolver.solverType = exu.LinearSolverType.EigenSparse
    return settings
