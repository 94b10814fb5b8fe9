"""MuJoCo as a kinematics engine: the driven mechanism is simulated with soft constraints.

build: the scenario becomes MJCF (adapters.mujoco.mjcf) through a planned tree, linear laws and cam
pairs; MuJoCo's own constraint rows assemble the start (adapters.mujoco.assembly); the model is
written a second time at the assembled poses, so qpos = 0 is the closed mechanism; the start state
is then reached by a short run-in from t = -RUN_IN steps. The build's time covers all of this, per
row; only the model's MJCF text with its start (Model.xml, what `export` writes) is left to its
first reading. simulate: steps MuJoCo on the output grid and reads poses from the body-frame
sites, velocities and accelerations from MuJoCo's state (mj_objectVelocity, and
mj_objectAcceleration on the qacc of a forward pass at the grid time).
Instability (a bad-acceleration warning, auto-reset disabled) is `diverged`.
A dynamic scenario carries gravity and its loads (adapters.mujoco.loads), starts from the
assembled poses and the bodies' rates without a run-in, and has its own settings
(adapters.mujoco.dynamics).

Settings: mode RK4 (default), implicitfast, Euler or implicit, or untuned (MuJoCo's own defaults,
adapters.mujoco.untuned); dt, the engine step (by default the rule's, adapters.step_rule and
adapters.mujoco.settings; the output grid never changes it: outputs between steps are reached by a
side step, adapters.lattice); tc, the solref time constant in seconds; solref, its form (time
constant, or stiffness and damping directly); invweight, the factor on the compiled model's
invweight0 that sets the regulariser (adapters.mujoco.weights: the closed loops' accuracy floor);
impedance, solimp of the equalities; for cams
preload (N), contact_impedance and, for a profile other than a disc, cam_pieces (its facets);
polynomial, how a polynomial drive of degree 2 to 4 is carried (adapters.mujoco.laws: polycoef,
the default, or a steered clock).
"""

from __future__ import annotations

import warnings

import mujoco
import numpy as np

from adapters.base import Adapter, Option, OptionValue, Setting, Unsupported
from adapters.lattice import check_grid, lattice_point
from adapters.modes import ADAPTER, ENGINE, Mode
from adapters.mujoco.cam_facets import DEFAULT_PIECES, MAX_PIECES, MIN_PIECES, PIECES_HELP, faceted, hops
from adapters.mujoco.cam_load import check_contacts, hop_allowances, knife_edge_reason, preload
from adapters.mujoco.cams import cam_pairs
from adapters.mujoco.compile import assembled_poses, clock_armatures, compile_model, follower_springs
from adapters.mujoco.controls import controls
from adapters.mujoco.dynamics import DYNAMIC_MODES, angle_columns, closes_loops
from adapters.mujoco.kinematics import KinematicSolver
from adapters.mujoco.knobs import KNOBS
from adapters.mujoco.laws import laws
from adapters.mujoco.loads import loads_of
from adapters.mujoco.mjcf import Physics
from adapters.mujoco.model import Model
from adapters.mujoco.pairs import collides
from adapters.mujoco.scale import dof_sizes, scale_of
from adapters.mujoco.settings import (
    DYNAMIC_TC_STEPS,
    IMPEDANCE,
    INVWEIGHT,
    KINEMATIC_MODES,
    OWN_TC_STEPS,
    SINGULAR_TC_STEPS,
    SOLREF_FORMS,
    STEPS_PER_PERIOD,
    TC_STEPS,
    UNTUNED,
    equality_solref,
    own_regulariser,
    probe_settings,
    rule_default,
    rule_ladder,
    time_constant,
)
from adapters.mujoco.simulation import advance, read_outputs, record, side_step, soften
from adapters.mujoco.tree import TreeError, plan_tree
from adapters.mujoco.untuned import untuned
from adapters.mujoco.weights import MUJOCO_S_OWN
from adapters.probes import Probe
from scenarios.cam_linkage import CAM_MODELS, cam_model_scenario, default_cam_model
from scenarios.registry import singular_passages
from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory

KINEMATIC = "kinematic"
SWEPT = ("dt", "tc", "impedance", "invweight", "solref")
"""The options the ladder's rungs set themselves (the default's others are carried onto each)."""
RUN_IN = 50
"""Steps run before t = 0 from the assembled start, so soft constraints begin in steady state."""
DYNAMIC_CAM_REASON = (
    "a cam contact in MuJoCo needs a preload spring on the follower, a force the scenario does not have"
)
SINGULAR_REASON = (
    "accelerations above 1e-8 by the rule: where the loops pass singular positions the regulariser, "
    "scaled by invweight from the compiled pose, is no longer small beside the loop's own inverse "
    "inertia and the loop sags (tc is short there, 32 steps, to pull it back); the smaller scale that "
    "would take it away makes other free loops unstable (docs/settings-rule.md)"
)
CAM_FORCES_REASON = (
    "forces not given: a cam's MuJoCo model adds what the scenario lacks (its equivalent linkage a "
    "link, its contact a preload spring), so its forces are the model's, not the scenario's"
)
POLYCOEF, STEERED = "polycoef", "steered"
"""A polynomial drive of degree 2 to 4: MuJoCo's quartic equality on a unit-rate clock, or a clock
steered along f(t) by its motor (adapters.mujoco.controls; the default). MuJoCo leaves out the
dJ/dt v term of joint and tendon equalities (doc/computation: it computes it for connect and weld
only), so polycoef's curvature P''(c) c'^2 is made up by the position feedback alone: the drive
lags by about P'' tc^2 (5e-5 rad on a slider-crank at 4 steps of time constant, 6e-2 at the rule's
128), where the steered clock's equality is linear; polycoef is swept at 4 steps with MuJoCo's own
regulariser."""
SOLIMP_WIDTH = 0.005
"""solimp's transition width in characteristic lengths (0.001 m on the nominal 0.2 m crank)."""


def _warn(message: str) -> None:
    warnings.warn(f"MuJoCo: {message.strip()}", RuntimeWarning, stacklevel=2)


class MujocoAdapter(Adapter):
    """MuJoCo (generalized coordinates, soft constraints) driven by clock joints."""

    name = "mujoco"
    colour = "#1f77b4"
    packages = ("mujoco",)
    measured = (
        *(
            Mode(
                name,
                ENGINE,
                f"MuJoCo's {name} integrator on soft constraints, poses, velocities and "
                "accelerations read from MuJoCo's state",
            )
            for name in ("RK4", "implicitfast", "Euler")
        ),
        Mode(
            "implicit",
            ENGINE,
            "MuJoCo's implicit integrator (velocity-implicit with the full force derivatives) on soft "
            "constraints, poses, velocities and accelerations read from MuJoCo's state",
        ),
        Mode(
            UNTUNED,
            ENGINE,
            "MuJoCo as a new user's model has it: its own default integrator, solref, solimp, solver "
            "tolerance and regulariser (adapters.mujoco.untuned), at the rule's step",
        ),
        Mode(
            "kinematic",
            ADAPTER,
            "Newton on MuJoCo's own constraint rows (efc_pos, efc_J) at each grid time (timing "
            "adapter-dominated: a Python Newton loop with least-squares solves)",
            (
                ("velocity", "solve on MuJoCo's efc_J"),
                ("acceleration", "solve on efc_J with MuJoCo's bias accelerations"),
            ),
        ),
    )
    dynamics = True
    rule = (
        f"RK4 at 1/{STEPS_PER_PERIOD} of the shortest period, the equalities' time constant tc = "
        f"{TC_STEPS:g} steps (in seconds; {DYNAMIC_TC_STEPS:g} in free dynamics, "
        f"{SINGULAR_TC_STEPS:g} through singular passages) with the regulariser's "
        f"invweight0 scaled by {INVWEIGHT:g}, "
        f"impedance {IMPEDANCE}; cams by contact keep MuJoCo's own regulariser and tc = "
        f"{OWN_TC_STEPS:g} steps; every scenario, whatever its size"
    )
    knobs = KNOBS
    options = (
        Option("dt", float, 0.0, 1.0, low_open=True, unit="s", help="integration step"),
        Option("tc", float, 0.0, 1e3, low_open=True, unit="s", help="solref time constant of the equalities"),
        Option("impedance", float, 0.0, 1.0, low_open=True, help="solimp of the equalities"),
        Option(
            "invweight",
            float,
            0.0,
            1.0,
            low_open=True,
            help="factor on the compiled model's invweight0, the regulariser's scale (1: MuJoCo's own)",
        ),
        Option(
            "solref",
            str,
            choices=SOLREF_FORMS,
            help="the equalities' solref as (tc, 1), or directly as (-1/tc^2, -2/tc)",
        ),
        Option("contact_impedance", float, 0.0, 1.0, low_open=True, help="solimp of cam contacts"),
        Option("preload", float, 0.0, 1e9, low_open=True, unit="N", help="follower spring preload"),
        Option(
            "cam_model", str, choices=CAM_MODELS, help="disc cams as their equivalent linkage, or as contacts"
        ),
        Option("cam_pieces", int, MIN_PIECES, MAX_PIECES, help=PIECES_HELP),
        Option(
            "polynomial",
            str,
            choices=(POLYCOEF, STEERED),
            help="polynomial drives of degree 2 to 4 through polycoef, or by a steered clock",
        ),
    )

    def version(self) -> str:
        return str(mujoco.__version__)

    def supports(self, scenario: Scenario) -> str | None:
        try:
            tree = plan_tree(scenario)
            laws(scenario, tree)
            cam_pairs(scenario.cams, tree)
            loads_of(scenario, tree)
        except TreeError as reason:
            return str(reason)
        if scenario.analysis == "dynamic" and scenario.cams and default_cam_model(scenario) == "contact":
            return DYNAMIC_CAM_REASON
        if default_cam_model(scenario) == "contact":
            return next(filter(None, map(knife_edge_reason, scenario.cams)), None)
        return None

    def default_setting(self, scenario: Scenario) -> Setting:
        setting = rule_default(scenario)
        if scenario.cams and scenario.analysis != "dynamic":
            setting = setting.replace(cam_model=default_cam_model(scenario))
            if setting["cam_model"] == "contact":
                setting = setting.replace(preload=preload(scenario), contact_impedance=0.99)
            if faceted(scenario):
                setting = setting.replace(cam_pieces=DEFAULT_PIECES)
        if _polycoef_drives(scenario):  # polycoef's lag grows as tc^2: a long tc needs the steered clock
            setting = setting.replace(polynomial=STEERED)
        return setting

    def default_reason(self, scenario: Scenario) -> str:
        return SINGULAR_REASON if scenario.analysis == "dynamic" and singular_passages(scenario) else ""

    def probe_settings(self, probe: Probe, scenario: Scenario) -> list[Setting] | None:
        return probe_settings(probe, scenario, self.default_setting(scenario))

    def ladder(self, scenario: Scenario) -> list[Setting]:
        dynamic = scenario.analysis == "dynamic"
        base = self.default_setting(scenario)
        built = cam_model_scenario(scenario, str(base.get("cam_model", default_cam_model(scenario))))
        rungs = rule_ladder(scenario, DYNAMIC_MODES if dynamic else KINEMATIC_MODES, closes_loops(built))
        extra = {k: v for k, v in base.options if k not in SWEPT}
        settings = [s.replace(**extra) if extra else s for s in rungs]
        steps = [s for s in settings if _on_step_ladder(s, base)]
        if base.get("cam_model") == "linkage":  # MuJoCo's own cam contact: its step ladders
            contact: dict[str, OptionValue] = {
                "cam_model": "contact",
                "preload": preload(scenario),
                "contact_impedance": 0.99,
            }
            settings += [own_regulariser(s).replace(**contact) for s in steps]
        if _polycoef_drives(scenario):  # the same drives through polycoef: RK4's step ladder at a short tc
            settings += [own_regulariser(s).replace(polynomial=POLYCOEF) for s in steps if s.mode == "RK4"]
        return settings

    def build(self, scenario: Scenario, setting: Setting) -> Model:
        mujoco.set_mju_user_warning(_warn)  # engine warnings become Python warnings the base class records
        reason = self.supports(scenario)
        if reason is not None:
            raise Unsupported(reason)
        kinematic = setting.mode == KINEMATIC
        dynamic = scenario.analysis == "dynamic"
        if dynamic and setting.mode not in (*DYNAMIC_MODES, UNTUNED):
            raise Unsupported(f"mode {setting.mode} is not a MuJoCo integrator of free dynamics")
        # A cam's model adds what the scenario lacks (a link of LINK_MASS, or a preload spring):
        # its forces would be the model's, so none are reported, and the row says why.
        own = set() if scenario.cams else {c.name for c in (*scenario.joints, *scenario.drivers)}
        if scenario.cams:
            warnings.warn(CAM_FORCES_REASON, stacklevel=2)
        try:
            scenario = cam_model_scenario(
                scenario, str(setting.get("cam_model", default_cam_model(scenario)))
            )
        except ValueError as error:
            raise Unsupported(str(error)) from error
        reason = next(filter(None, map(knife_edge_reason, scenario.cams)), None)
        if dynamic and scenario.cams:
            reason = DYNAMIC_CAM_REASON
        if reason is not None:
            raise Unsupported(reason)
        dt = float(setting.get("dt", rule_default(scenario)["dt"]))
        physics = Physics(
            "RK4" if kinematic else setting.mode,
            dt,
            equality_solref(setting, dt),
            _solimp(float(setting.get("impedance", 0.9999)), scenario.characteristic_length),
            _solimp(float(setting.get("contact_impedance", 0.99)), scenario.characteristic_length),
            cam_pieces=int(setting.get("cam_pieces", DEFAULT_PIECES)),
            steer=setting.get("polynomial", POLYCOEF) == STEERED,
            contact_solref=(time_constant(setting, dt), 1.0),
            invweight=float(setting.get("invweight", MUJOCO_S_OWN)),
        )
        if dynamic and singular_passages(scenario) and float(setting.get("invweight", 1.0)) < 1.0:
            warnings.warn(SINGULAR_REASON, stacklevel=2)
        if setting.mode == UNTUNED:
            physics = untuned(physics)
        run_in = 0 if kinematic or dynamic else RUN_IN
        scale = scale_of(scenario)
        guessed = plan_tree(scenario)
        physics = Physics(**{**physics.__dict__, "loads": loads_of(scenario, guessed)})
        first = compile_model(scenario, guessed, physics, 0, scale, linear=True)
        poses = assembled_poses(scenario, guessed, first)
        tree = plan_tree(scenario, poses)
        load = float(setting.get("preload", preload(scenario)))
        springs = follower_springs(scenario, first, tree, load, scale, physics.cam_pieces)
        armatures = clock_armatures(scenario, guessed, first, scale, physics.steer)
        loads = loads_of(scenario, tree)
        sized = Physics(
            **{**physics.__dict__, "springs": springs, "clock_armature": armatures, "loads": loads}
        )
        built = compile_model(scenario, tree, sized, run_in, scale)
        built.preload = load
        built.forces = built.forces.only(own)
        built.hops = hop_allowances(built.model, built.qpos0, hops(scenario.cams, physics.cam_pieces))
        if dynamic:
            built.loads, built.angles = loads, scenario
        if kinematic:
            built.kinematic = KinematicSolver(built.model, built.clocks, dof_sizes(built.model, scale))
        return built

    def simulate(self, model: Model, times: np.ndarray) -> Trajectory:
        m = model.model
        grid = np.asarray(times, dtype=float)
        if model.kinematic is not None:
            return self._kinematic(model, grid)
        check_grid(grid, 0.0)
        dt = model.dt
        soften(m, model)
        d = mujoco.MjData(m)
        d.qpos[:], d.qvel[:] = model.qpos0, model.qvel0
        n, k = len(grid), len(model.bodies)
        pos, vel, acc = np.empty((n, k, 3)), np.empty((n, k, 3)), np.empty((n, k, 3))
        columns = model.forces.columns()
        forces = np.empty((n, len(columns)))
        done = 0  # whole steps from t = 0: the lattice every output time is read from
        cams = collides(m)
        with controls(m, d, model.loads.motors, model.clocks):
            mujoco.mj_forward(m, d)
            for i, t in enumerate(grid):
                whole, rest = lattice_point(0.0, float(t), dt)
                if whole > done:
                    advance(m, d, whole - done)
                    self.count_steps(whole - done)
                    done = whole
                with side_step(m, d, rest):
                    self.count_steps(1 if rest > 0.0 else 0)
                    record(m, d, model, pos[i], vel[i], acc[i])
                    forces[i] = model.forces.read(m, d)
                    if cams:
                        check_contacts(m, d, model.preload, model.hops, model.pairs)
        extras = angle_columns(model.angles, model.bodies, pos[:, :, 2]) if model.angles else {}
        extras.update(zip(columns, forces.T, strict=True))
        return Trajectory(grid, model.bodies, pos, vel, acc, extras=extras)

    def _kinematic(self, model: Model, grid: np.ndarray) -> Trajectory:
        """MuJoCo's rows solved at each grid time (adapters.mujoco.kinematics)."""
        assert model.kinematic is not None
        m = model.model
        d = mujoco.MjData(m)
        d.qpos[:] = model.qpos0
        n, k = len(grid), len(model.bodies)
        pos, vel, acc = np.empty((n, k, 3)), np.empty((n, k, 3)), np.empty((n, k, 3))
        for i, t in enumerate(grid):
            model.kinematic.solve(d, float(t))
            read_outputs(m, d, model, pos[i], vel[i], acc[i])
        self.count_steps(n)
        return Trajectory(grid, model.bodies, pos, vel, acc)

    def export(self, scenario: Scenario, setting: Setting, path: str) -> None:
        built = self.build(scenario, setting)
        with open(path, "w", encoding="utf-8") as stream:
            stream.write(built.xml)


def _polycoef_drives(scenario: Scenario) -> bool:
    """Whether a drive of the scenario goes through polycoef by default."""
    try:
        return any(not law.linear for law in laws(scenario, plan_tree(scenario)))
    except TreeError:
        return False


def _on_step_ladder(setting: Setting, base: Setting) -> bool:
    """Whether `setting` is a rung of a step ladder: an integrator at the default's time constant
    in steps, regulariser, solref form and impedance."""
    if setting.mode == UNTUNED or any(setting.get(k) != base.get(k) for k in SWEPT[2:]):
        return False
    steps = float(setting["tc"]) / float(setting["dt"])
    return abs(steps - float(base["tc"]) / float(base["dt"])) <= 1e-9 * steps


def _solimp(impedance: float, length: float) -> tuple[float, float, float, float, float]:
    """A constant impedance (the width, a distance, matters only where the two differ: sized by the
    mechanism all the same)."""
    return (impedance, impedance, SOLIMP_WIDTH * length, 0.5, 2.0)
