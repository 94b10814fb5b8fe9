"""Pinocchio adapter: the mechanism as a kinematic tree in relative joint coordinates.

The tree spans the scenario's joints from the ground (revolute joints about z, prismatic joints in
the plane); the remaining joints, gears and cam contacts close loops as rows built from Pinocchio's
frame placements and Jacobians; gear pairs on a common carrier are mimic joints where Pinocchio can
hold them. Four modes (Setting.mode):
- `kinematic`: Newton on the loop and driver rows at every output time, velocities and accelerations
  from the same Jacobian and Pinocchio's classical accelerations. Option `tol` (residual bound, in
  each row's size: lengths relative to the characteristic length, angles in radians) and `gears`
  (`mimic` or `row`).
- `dynamic`: `constraintDynamics` with the loops as Pinocchio constraint models and the drive as a
  constraint, integrated with RK4. Options `dt` (step, default by the rule of adapters.step_rule:
  1/1000 of the shortest period of the motion), `kp` and `kd` (Baumgarte gains, default 0).
- `baumgarte`: the dynamic mode with gains kp = w^2, kd = 2 w by default (w the drive frequency):
  a critically damped correction of constraint and drive drift with a time constant of one radian
  of the shortest period.
- `euler`: the Baumgarte-stabilised dynamics marched by semi-implicit Euler (first order).
Free dynamic scenarios (no driver) carry their gravity and loads (adapters.pinocchio.loads), start
from the scenario's assembled bodies (adapters.pinocchio.free_start) and step by the same rule
(1/10000 of the period for Euler); their default is `baumgarte`. The output grid never sets the
step (adapters.pinocchio.settings, adapters.lattice).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from typing import Any

import numpy as np
import pinocchio as pin

from adapters.base import Adapter, EngineFailure, Option, Setting, Unsupported
from adapters.modes import ADAPTER, ENGINE, Mode
from adapters.pinocchio.cam_dynamics import CamDynamicSolver
from adapters.pinocchio.constraint_rows import ConstraintRows
from adapters.pinocchio.dynamics import DynamicSolver, dynamic_support
from adapters.pinocchio.forces import ForceReader
from adapters.pinocchio.forces import unsupported as forces_unsupported
from adapters.pinocchio.free_start import free_start
from adapters.pinocchio.kinematics import KinematicSolver, body_motion
from adapters.pinocchio.knobs import KNOBS
from adapters.pinocchio.loads import Loads
from adapters.pinocchio.model import PinModel, build_model
from adapters.pinocchio.row_dynamics import RowDynamicSolver
from adapters.pinocchio.settings import (
    BAUMGARTE,
    DYNAMIC,
    EULER,
    KINEMATIC,
    PER_PERIOD,
    STEPS_PER_PERIOD,
    dynamic_ladder,
    probe_settings,
    rule_setting,
)
from adapters.pinocchio.settings import gains as default_gains
from adapters.pinocchio.simulation import EULER as EULER_METHOD
from adapters.pinocchio.simulation import RK4
from adapters.pinocchio.tree import Tree, TreeError, plan
from adapters.probes import Probe
from adapters.step_rule import rule_step
from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory

MODES = {
    "kinematic": KINEMATIC,
    "dynamic": DYNAMIC,
    "baumgarte": BAUMGARTE,
    "euler": EULER,
}
_SHARE = (
    "timing adapter-dominated: Pinocchio's kernels are a minority of a step in free dynamics "
    "(their share measured by python -m benchmarks.pinocchio_dynamics)"
)
MEASURED = (
    Mode(
        "kinematic",
        ADAPTER,
        "Newton on loop and driver rows from Pinocchio's frame placements and Jacobians (timing "
        "adapter-dominated: most of the run is the adapter's Newton loop, not Pinocchio's calls)",
        (
            ("velocity", "adapter solve on Pinocchio's Jacobians"),
            ("acceleration", "adapter solve with Pinocchio's classical accelerations"),
        ),
    ),
    Mode(
        "dynamic",
        ENGINE,
        "Pinocchio's constrained dynamics (constraintDynamics on revolute loops, forwardDynamics on "
        "the adapter's rows for gears, sliding lines and cams with phi eliminated, aba on a tree), "
        f"integrated by RK4 in the adapter ({_SHARE})",
    ),
    Mode(
        "baumgarte",
        ENGINE,
        f"the dynamic mode with Baumgarte gains on the rows, integrated by RK4 in the adapter ({_SHARE})",
    ),
    Mode(
        "euler",
        ENGINE,
        "Pinocchio's constrained dynamics with Baumgarte gains, marched by semi-implicit Euler "
        f"around pin.integrate (the loop of Pinocchio's simulation examples; {_SHARE})",
    ),
)
TOLERANCES = (1e-5, 1e-9, 1e-15)
"""Newton residual bounds in the kinematic ladder; the default is the last."""


@dataclass
class Built:
    """What `build` hands to `simulate`."""

    scenario: Scenario
    mode: str
    pm: PinModel
    kinematics: KinematicSolver
    dynamics: DynamicSolver | None
    start: tuple[float, np.ndarray, np.ndarray] | None = None
    """(t0, z0, v0): the consistent start found at build time, outside the timed run."""
    forces: ForceReader | None = None
    """Reads the driving forces and reactions at the run's states; None where it cannot."""


class PinocchioAdapter(Adapter):
    name = "pinocchio"
    colour = "#2ca02c"
    packages = ("pin",)
    rule = (
        "kinematic scenarios: Newton at each output time (no step, tol 1e-15); free dynamics: "
        f"baumgarte (RK4) at 1/{STEPS_PER_PERIOD[BAUMGARTE]} of the shortest period, gains critically "
        "damped at one radian of it"
    )
    measured = MEASURED
    dynamics = True
    knobs = KNOBS
    options = (
        Option("tol", float, 0.0, 1.0, low_open=True, help="Newton residual bound, in the rows' sizes"),
        Option("gears", str, choices=("mimic", "row"), help="gears as mimic joints or coupling rows"),
        Option("dt", float, 0.0, 1.0, low_open=True, unit="s", help="integration step"),
        Option("kp", float, 0.0, 1e12, help="Baumgarte position gain"),
        Option("kd", float, 0.0, 1e12, help="Baumgarte velocity gain"),
    )

    def version(self) -> str:
        return str(pin.__version__)

    def supports(self, scenario: Scenario) -> str | None:
        try:
            self._structure(scenario, mimic_gears=False)
        except Unsupported as reason:
            return str(reason)
        return None

    def default_setting(self, scenario: Scenario) -> Setting:
        if scenario.analysis == "dynamic":
            # Baumgarte by default: RK4 without it drifts off the loops and diverges where the
            # constraints turn singular (n_four_bar at t = 3.18 s); Pinocchio's maintainers
            # recommend the gains against constraint drift
            return self.free_setting(scenario, BAUMGARTE)
        return Setting.of(KINEMATIC, tol=TOLERANCES[-1], gears="mimic")

    def free_setting(
        self, scenario: Scenario, mode: str = DYNAMIC, steps_per_period: float | None = None
    ) -> Setting:
        """A setting of `mode` at `steps_per_period` steps per shortest period of the motion
        (adapters.step_rule; default: the mode's constant, adapters.pinocchio.settings)."""
        return rule_setting(scenario, mode, steps_per_period)

    def dynamic_setting(
        self, scenario: Scenario, steps_per_period: int = 1000, mode: str = DYNAMIC
    ) -> Setting:
        """A dynamic-mode setting with `steps_per_period` RK4 steps per shortest period."""
        return rule_setting(scenario, mode, steps_per_period)

    def probe_settings(self, probe: Probe, scenario: Scenario) -> list[Setting] | None:
        return probe_settings(probe, scenario, self.default_setting(scenario))

    def ladder(self, scenario: Scenario) -> list[Setting]:
        if scenario.analysis == "dynamic":
            return dynamic_ladder(scenario)
        settings = [self.default_setting(scenario).replace(tol=tol) for tol in TOLERANCES]
        # cams run in the dynamic modes too, but their contact solve per evaluation makes a step
        # cost 5-15 ms of Python: swept only on request
        if self.supports(scenario) is None and not scenario.cams:
            for mode in (DYNAMIC, BAUMGARTE):
                settings += [rule_setting(scenario, mode, n) for n in PER_PERIOD[mode][:3]]
        return settings

    def _structure(self, scenario: Scenario, mimic_gears: bool) -> tuple[Tree, PinModel, ConstraintRows]:
        """The tree, the Pinocchio model and the constraint rows; Unsupported if they do not make a square
        system in the unknowns (kinematic scenarios) or leave no freedom (dynamic ones)."""
        dynamic = scenario.analysis == "dynamic"
        if dynamic and scenario.cams:
            raise Unsupported(
                "free dynamics with a cam needs a unilateral contact; the adapter's cam rows are "
                "bilateral kinematic constraints"
            )
        try:
            tree = plan(scenario, mimic_gears)
        except TreeError as error:
            raise Unsupported(str(error)) from None
        pm = build_model(scenario, tree)
        constraint_rows = ConstraintRows.of(scenario, pm)
        solver = KinematicSolver(pm, constraint_rows, length=scenario.characteristic_length)
        count = (
            constraint_rows.evaluate(solver.snapshot(self._guess(scenario, pm))).val.size
            if constraint_rows.closures or constraint_rows.drivers
            else 0
        )
        unknowns = pm.model.nq + len(scenario.cams)
        if dynamic and count >= unknowns:
            raise Unsupported(
                f"the loop-closure and driver rows ({count}) leave no freedom to the {unknowns} joint "
                "coordinates"
            )
        if not dynamic and count != unknowns:
            raise Unsupported(
                f"the loop-closure and driver rows ({count}) do not match the unknowns ({unknowns}): "
                "not a kinematically driven mechanism"
            )
        return tree, pm, constraint_rows

    @staticmethod
    def _guess(scenario: Scenario, pm: PinModel) -> np.ndarray:
        return np.concatenate([pm.q_guess(), [c.phi_guess for c in scenario.cams]])

    def build(self, scenario: Scenario, setting: Setting) -> Built:
        mode = MODES.get(setting.mode)
        if mode is None:
            raise EngineFailure(f"unknown Pinocchio mode '{setting.mode}'; known: {', '.join(MODES)}")
        if mode == KINEMATIC and scenario.analysis == "dynamic":
            raise EngineFailure(
                "the kinematic mode solves driven mechanisms; free dynamics runs in dynamic, baumgarte "
                "or euler"
            )
        gears = str(setting.get("gears", "mimic"))
        tree, pm, constraint_rows = self._structure(
            scenario, mimic_gears=mode == KINEMATIC and gears == "mimic"
        )
        tol = float(setting.get("tol", TOLERANCES[-1]))
        kinematics = KinematicSolver(
            pm,
            constraint_rows,
            tol=tol if mode == KINEMATIC else TOLERANCES[-1],
            length=scenario.characteristic_length,
        )
        dynamics: DynamicSolver | None = None
        if mode != KINEMATIC:
            dt = float(setting.get("dt", rule_step(scenario, STEPS_PER_PERIOD[mode])))
            kp, kd = default_gains(scenario, mode)
            gains = float(setting.get("kp", kp)), float(setting.get("kd", kd))
            # revolute loops as Pinocchio's own constraint models; any other rows through forwardDynamics
            loads = Loads(pm, scenario.forces) if scenario.forces else None
            method = EULER_METHOD if mode == EULER else RK4
            if scenario.cams:  # the contact parameters eliminated from forwardDynamics' rows
                phi0 = self._guess(scenario, pm)[pm.model.nq :]
                dynamics = CamDynamicSolver(kinematics, phi0, dt, gains, loads, method)
            else:
                solver = DynamicSolver if dynamic_support(scenario, tree) is None else RowDynamicSolver
                dynamics = solver(pm, constraint_rows, dt, gains, loads, method)
        built = Built(scenario, mode, pm, kinematics, dynamics)
        missing = forces_unsupported(scenario, pm, constraint_rows)
        if missing is None:
            built.forces = ForceReader(scenario, pm, constraint_rows)
        else:  # named in the row's warnings
            warnings.warn(missing, stacklevel=2)
        built.start = self._start(built, float(scenario.times()[0]))
        return built

    def _start(self, built: Built, t0: float) -> tuple[float, np.ndarray, np.ndarray]:
        """The consistent start at t0 on Pinocchio's rows (positions, and velocities for dynamics)."""
        if built.dynamics is not None and not built.scenario.drivers:
            return (t0, *free_start(built.scenario, built.kinematics))
        z0 = built.kinematics.assemble(self._guess(built.scenario, built.pm), t0)
        if built.dynamics is None:
            return t0, z0, np.zeros(0)
        _, factor = built.kinematics.position(z0, t0)
        return t0, z0, built.kinematics.rates(z0, factor, t0)[0]

    def export(self, scenario: Scenario, setting: Setting, path: str) -> None:
        """Pinocchio's own serialization of the kinematic tree, frames and mimic joints (Boost XML;
        reload with `pinocchio.Model().loadFromXML(path, "model")`). Loop closures, coupling rows and
        cam contacts are rows the adapter solves: they are not part of a Pinocchio model file."""
        reason = self.supports(scenario)
        if reason is not None:
            raise Unsupported(reason)
        self.build(scenario, setting).pm.model.saveToXML(str(path), "model")

    def simulate(self, model: Any, times: np.ndarray) -> Trajectory:
        built: Built = model
        scenario, pm, kin = built.scenario, built.pm, built.kinematics
        start = built.start
        if start is None or start[0] != float(times[0]):
            start = self._start(built, float(times[0]))
        _, z0, v0 = start
        nq = pm.model.nq
        if built.dynamics is None:
            z, z_rate, z_acc = kin.run(z0, times)
            self.count_steps(len(times))
            q, v, a = z[:, :nq], z_rate[:, :nq], z_acc[:, :nq]
        else:
            if isinstance(built.dynamics, CamDynamicSolver):
                built.dynamics.restart(z0[nq:])  # each run from the start's contact parameters
            q, v, a, steps = built.dynamics.run(z0[:nq], v0[:nq], times)
            self.count_steps(steps)
            z = q
            if isinstance(built.dynamics, CamDynamicSolver):
                built.dynamics.restart(z0[nq:])
                phi = [built.dynamics.solve_phi(q[k], float(times[k])) for k in range(len(times))]
                z = np.concatenate([q, np.array(phi)], axis=1)
        bodies = scenario.output_bodies
        data = pm.model.createData()
        levels = np.stack([body_motion(pm, data, (q[k], v[k], a[k]), bodies) for k in range(len(times))])
        extras = {f"{c.name}.phi": z[:, nq + k].copy() for k, c in enumerate(scenario.cams)}
        extras.update(_forces(built, q, v, a, times))
        for column in scenario.angle_outputs:  # Andrews' joint angles from Pinocchio's body angles
            body, base = column.body, column.relative_to
            extras[column.name] = np.array([pm.angle(body, qk) - pm.angle(base, qk) for qk in q])
        grid = np.asarray(times, dtype=float)
        return Trajectory(grid, bodies, levels[:, 0], levels[:, 1], levels[:, 2], extras)


def _forces(
    built: Built, q: np.ndarray, v: np.ndarray, a: np.ndarray, times: np.ndarray
) -> dict[str, np.ndarray]:
    """Every driving force and joint reaction at the grid states (adapters.pinocchio.forces); none
    where the model's forces cannot be read (the build warns why: `forces_unsupported`)."""
    if built.forces is None:
        return {}
    found = np.array([built.forces.read(float(t), q[k], v[k], a[k]) for k, t in enumerate(times)])
    return {label: found[:, k].copy() for k, label in enumerate(built.forces.columns())}
