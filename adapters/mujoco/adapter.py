"""MuJoCo as a kinematics engine: the driven mechanism is simulated with soft constraints.

build: the scenario becomes MJCF (adapters.mujoco.mjcf) through a planned tree, linear laws and cam
pairs; MuJoCo's own constraint rows assemble the start (adapters.mujoco.assembly); the model is
written a second time at the assembled poses, so qpos = 0 is the closed mechanism; the start state
is then reached by a short run-in from t = -RUN_IN steps. simulate: steps MuJoCo on the output
grid and reads poses from the body-frame sites, velocities and accelerations from MuJoCo's state
(mj_objectVelocity, and mj_objectAcceleration on the qacc of a forward pass at the grid time).
Instability (a bad-acceleration warning, auto-reset disabled) is `diverged`.
A dynamic scenario carries gravity and its loads (adapters.mujoco.loads), starts from the
assembled poses and the bodies' rates without a run-in, and has its own settings
(adapters.mujoco.dynamics).

Settings: mode RK4 (default), implicitfast, Euler or implicit; dt, the requested step (the engine step divides
the output interval); tc_steps, the solref time constant in steps (2, the smallest MuJoCo allows);
impedance, solimp of the equalities; for cams preload (N) and contact_impedance.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import mujoco
import numpy as np

from adapters.base import Adapter, Diverged, Option, Setting, Unsupported
from adapters.modes import ADAPTER, ENGINE, Mode
from adapters.mujoco.assembly import assemble, clock_velocities, contact_slopes, settle
from adapters.mujoco.cam_load import check_contacts, knife_edge_reason, preload
from adapters.mujoco.cams import CamPair, cam_pairs
from adapters.mujoco.dynamics import (
    DYNAMIC_MODES,
    angle_columns,
    controls,
    dynamic_default,
    dynamic_sweep,
    rate_velocities,
)
from adapters.mujoco.kinematic import KinematicSolver
from adapters.mujoco.laws import Clock, Law, laws
from adapters.mujoco.loads import Loads, loads_of
from adapters.mujoco.mjcf import Physics, mjcf
from adapters.mujoco.scale import Scale, clock_armature, dof_sizes, scale_of
from adapters.mujoco.tree import Affine, Tree, TreeError, angle, plan_tree
from scenarios.bodies import Pose
from scenarios.cam_linkage import CAM_MODELS, cam_model_scenario, default_cam_model
from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory

MODES = ("RK4", "implicitfast", "Euler", "kinematic", "implicit")
KINEMATIC = "kinematic"
SWEEP_DT = (1e-3, 1e-4, 1e-5)
BAD = (mujoco.mjtWarning.mjWARN_BADQACC, mujoco.mjtWarning.mjWARN_BADQPOS, mujoco.mjtWarning.mjWARN_BADQVEL)
STATE = mujoco.mjtState.mjSTATE_INTEGRATION
RUN_IN = 50
DYNAMIC_CAM_REASON = (
    "a cam contact in MuJoCo needs a preload spring on the follower, a force the scenario does not have"
)
SOLIMP_WIDTH = 0.005
"""solimp's transition width in characteristic lengths (0.001 m on the nominal 0.2 m crank)."""
"""Steps run before t = 0 from the assembled start, so soft constraints begin in steady state."""


@dataclass
class Model:
    """A compiled MuJoCo model with its consistent start and what the outputs need."""

    xml: str
    model: mujoco.MjModel
    qpos0: np.ndarray
    qvel0: np.ndarray
    dt: float
    tc_steps: float
    bodies: tuple[str, ...]
    sites: list[int]
    theta: list[Affine]
    joint_ids: dict[str, int]
    clocks: dict[int, Clock]
    preload: float = 0.0
    """The cam followers' preload (N); 0 without cams."""
    kinematic: KinematicSolver | None = None
    """The solver of the kinematic mode (None: MuJoCo's integrator)."""
    loads: Loads = field(default_factory=Loads)
    """The dynamic scene's loads, whose motors' controls simulate sets."""
    angles: Scenario | None = None
    """The scenario whose angle outputs the trajectory carries (None: none)."""


def _warn(message: str) -> None:
    warnings.warn(f"MuJoCo: {message.strip()}", RuntimeWarning, stacklevel=2)


class MujocoAdapter(Adapter):
    """MuJoCo (generalized coordinates, soft constraints) driven by clock joints."""

    name = "mujoco"
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
    modes = MODES
    dynamics = True
    options = (
        Option("dt", float, 0.0, 1.0, low_open=True, unit="s", help="integration step"),
        Option("tc_steps", float, 1.0, 1e6, help="solref time constant of the equalities, in steps"),
        Option("impedance", float, 0.0, 1.0, low_open=True, help="solimp of the equalities"),
        Option("contact_impedance", float, 0.0, 1.0, low_open=True, help="solimp of cam contacts"),
        Option("preload", float, 0.0, 1e9, low_open=True, unit="N", help="follower spring preload"),
        Option(
            "cam_model", str, choices=CAM_MODELS, help="disc cams as their equivalent linkage, or as contacts"
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
        if scenario.analysis == "dynamic":
            return dynamic_default(scenario)
        options: dict[str, float] = {"dt": 1e-4, "tc_steps": 2.0, "impedance": 0.9999}
        setting = Setting.of("RK4", **options)
        if scenario.cams:
            setting = setting.replace(cam_model=default_cam_model(scenario))
            if setting["cam_model"] == "contact":
                setting = setting.replace(preload=preload(scenario), contact_impedance=0.99)
        return setting

    def sweep(self, scenario: Scenario) -> list[Setting]:
        if scenario.analysis == "dynamic":
            return dynamic_sweep(scenario)
        base = self.default_setting(scenario)
        bases = [base]
        if base.get("cam_model") == "linkage":  # MuJoCo's own cam contact as curves of their own
            bases.append(base.replace(cam_model="contact", preload=preload(scenario), contact_impedance=0.99))
        return [
            Setting(mode, b.options).replace(dt=dt)
            for b in bases
            for mode in ("RK4", "implicitfast")
            for dt in SWEEP_DT
        ]

    def build(self, scenario: Scenario, setting: Setting) -> Model:
        mujoco.set_mju_user_warning(_warn)  # engine warnings become Python warnings the base class records
        reason = self.supports(scenario)
        if reason is not None:
            raise Unsupported(reason)
        kinematic = setting.mode == KINEMATIC
        dynamic = scenario.analysis == "dynamic"
        if dynamic and setting.mode not in DYNAMIC_MODES:
            raise Unsupported(f"mode {setting.mode} is not a MuJoCo integrator of free dynamics")
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
        dt = engine_step(float(setting.get("dt", 1e-4)), _interval(np.asarray(scenario.times())))
        physics = Physics(
            "RK4" if kinematic else setting.mode,
            dt,
            (float(setting.get("tc_steps", 2.0)) * dt, 1.0),
            _solimp(float(setting.get("impedance", 0.9999)), scenario.characteristic_length),
            _solimp(float(setting.get("contact_impedance", 0.99)), scenario.characteristic_length),
        )
        run_in = 0 if kinematic or dynamic else RUN_IN
        scale = scale_of(scenario)
        guessed = plan_tree(scenario)
        physics = Physics(**{**physics.__dict__, "loads": loads_of(scenario, guessed)})
        first = _compile(scenario, guessed, physics, 0, scale)
        poses = _poses(scenario, guessed, first)
        tree = plan_tree(scenario, poses)
        load = float(setting.get("preload", preload(scenario)))
        springs = _springs(scenario, first, tree, load, scale)
        armatures = _armatures(scenario, guessed, first, scale)
        loads = loads_of(scenario, tree)
        sized = Physics(
            **{**physics.__dict__, "springs": springs, "clock_armature": armatures, "loads": loads}
        )
        built = _compile(scenario, tree, sized, run_in, scale)
        built.preload = load
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
        interval = _interval(grid)
        dt = engine_step(model.dt, interval) if interval else model.dt
        substeps = max(1, round(interval / dt)) if interval else 1
        _soften(m, dt, model.tc_steps)
        d = mujoco.MjData(m)
        d.qpos[:], d.qvel[:] = model.qpos0, model.qvel0
        n, k = len(grid), len(model.bodies)
        pos, vel, acc = np.empty((n, k, 3)), np.empty((n, k, 3)), np.empty((n, k, 3))
        with controls(m, d, model.loads.motors):
            mujoco.mj_forward(m, d)
            lead = round(grid[0] / dt) if grid.size else 0
            if lead:
                _advance(m, d, lead)
                self.count_steps(lead)
            for i in range(n):
                if i:
                    _advance(m, d, substeps)
                    self.count_steps(substeps)
                _record(m, d, model, pos[i], vel[i], acc[i])
                if m.npair:
                    check_contacts(m, d, model.preload)
        extras = angle_columns(model.angles, model.bodies, pos[:, :, 2]) if model.angles else {}
        return Trajectory(grid, model.bodies, pos, vel, acc, extras=extras)

    def _kinematic(self, model: Model, grid: np.ndarray) -> Trajectory:
        """MuJoCo's rows solved at each grid time (adapters.mujoco.kinematic)."""
        assert model.kinematic is not None
        m = model.model
        d = mujoco.MjData(m)
        d.qpos[:] = model.qpos0
        n, k = len(grid), len(model.bodies)
        pos, vel, acc = np.empty((n, k, 3)), np.empty((n, k, 3)), np.empty((n, k, 3))
        for i, t in enumerate(grid):
            model.kinematic.solve(d, float(t))
            _read(m, d, model, pos[i], vel[i], acc[i])
        self.count_steps(n)
        return Trajectory(grid, model.bodies, pos, vel, acc)

    def export(self, scenario: Scenario, setting: Setting, path: str) -> None:
        built = self.build(scenario, setting)
        with open(path, "w", encoding="utf-8") as stream:
            stream.write(built.xml)


def engine_step(requested: float, interval: float) -> float:
    """The largest step not above `requested` that divides the output interval."""
    if interval <= 0.0:
        return requested
    return interval / math.ceil(interval / requested - 1e-9)


def _solimp(impedance: float, length: float) -> tuple[float, float, float, float, float]:
    """A constant impedance (the width, a distance, matters only where the two differ: sized by the
    mechanism all the same)."""
    return (impedance, impedance, SOLIMP_WIDTH * length, 0.5, 2.0)


def _interval(grid: np.ndarray) -> float:
    if grid.size < 2:
        return 0.0
    steps = np.diff(grid)
    if np.ptp(steps) > 1e-9 * steps.mean() or grid[0] < 0.0:
        raise ValueError("MuJoCo needs an equally spaced time grid from t >= 0")
    return float(steps.mean())


def _compile(scenario: Scenario, tree: Tree, physics: Physics, run_in: int, scale: Scale) -> Model:
    """Compile the model for `tree` and find its start at t = 0, kept as the key 'start': the
    mechanism is assembled at t = -run_in steps (stepping back from t = 0 so that Newton stays on the
    assembled branch; preloaded contacts settled) and run in to t = 0, so
    that the soft constraints start in their own steady state rather than in a transient."""
    found = laws(scenario, tree)
    cams = cam_pairs(scenario.cams, tree)
    m = mujoco.MjModel.from_xml_string(mjcf(scenario, tree, found, cams, physics))
    d = mujoco.MjData(m)
    clocks = _clocks(m, found, 0.0)
    assemble(m, d, clocks, scale)
    for t in -physics.timestep * np.arange(1, run_in + 1):
        clocks = _clocks(m, found, float(t))
        assemble(m, d, clocks, scale)
    if m.npair:
        settle(m, d, clocks)
    if scenario.analysis == "dynamic":
        sites = [mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_SITE, b.name) for b in scenario.bodies]
        rate_velocities(m, d, sites, np.array([b.rate for b in scenario.bodies], dtype=float))
    if run_in:
        d.time = -run_in * physics.timestep
        _advance(m, d, run_in)
        d.time = 0.0
    xml = mjcf(scenario, tree, found, cams, physics, (d.qpos.copy(), d.qvel.copy()))
    outputs = scenario.output_bodies
    return Model(
        xml=xml,
        model=m,
        qpos0=d.qpos.copy(),
        qvel0=d.qvel.copy(),
        dt=physics.timestep,
        tc_steps=physics.solref[0] / physics.timestep,
        bodies=outputs,
        sites=[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_SITE, b) for b in outputs],
        theta=[angle(tree, b) for b in outputs],
        joint_ids={m.joint(j).name: m.jnt_dofadr[j] for j in range(m.njnt)},
        clocks={int(m.jnt_dofadr[m.joint(law.clock.joint).id]): law.clock for law in found if law.clock},
    )


def _clocks(m: mujoco.MjModel, found: list[Law], t: float) -> dict[int, tuple[float, float]]:
    """Each clock's dof and its (qpos, qvel) at time t."""
    clocks = [law.clock for law in found if law.clock is not None]
    return {int(m.jnt_dofadr[m.joint(c.joint).id]): c.at(t) for c in clocks}


def _poses(scenario: Scenario, tree: Tree, model: Model) -> dict[str, Pose]:
    """Every body's frame pose at the assembled start (angles continuous with the tree's)."""
    m = model.model
    d = mujoco.MjData(m)
    d.qpos[:] = model.qpos0
    mujoco.mj_kinematics(m, d)
    poses: dict[str, Pose] = {}
    for body in scenario.body_names:
        x, y = d.site_xpos[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_SITE, body)][:2]
        poses[body] = (float(x), float(y), _evaluate(angle(tree, body), model, model.qpos0))
    return poses


def _evaluate(form: Affine, model: Model, qpos: np.ndarray) -> float:
    return form.const + sum(c * float(qpos[model.joint_ids[j]]) for j, c in form.coefs.items())


def _armatures(scenario: Scenario, tree: Tree, model: Model, scale: Scale) -> dict[str, float]:
    """Each clock's armature, sized by the inertia it drives at the assembled start."""
    names = [law.clock.joint for law in laws(scenario, tree) if law.clock is not None]
    m = model.model
    d = mujoco.MjData(m)
    d.qpos[:], d.qvel[:] = model.qpos0, model.qvel0
    mujoco.mj_forward(m, d)
    dofs = [model.joint_ids[name] for name in names]
    speeds = clock_velocities(m, d, dofs, scale)
    return {name: clock_armature(m, d, qvel, dofs) for name, qvel in zip(names, speeds, strict=True)}


def _springs(
    scenario: Scenario, model: Model, tree: Tree, preload: float, scale: Scale
) -> dict[str, tuple[float, float]]:
    """A follower spring per cam pushing with `preload` into the contact at the start; it stiffens
    by 10 % over a characteristic length."""
    if not scenario.cams:
        return {}
    m = model.model
    d = mujoco.MjData(m)
    d.qpos[:], d.qvel[:] = model.qpos0, model.qvel0
    slopes = contact_slopes(m, d, scale)
    pairs: list[CamPair] = cam_pairs(scenario.cams, tree)
    springs = {}
    stiffness = preload / (10.0 * scenario.characteristic_length)
    for index, pair in enumerate(pairs):
        dof = model.joint_ids[pair.spring_joint]
        slope = slopes.get(index)
        if slope is None or slope[dof] == 0.0:
            raise Unsupported(f"cam '{pair.name}': the follower's joint does not move it off the cam")
        springs[pair.spring_joint] = (stiffness, -math.copysign(preload / stiffness, slope[dof]))
    return springs


def _soften(m: mujoco.MjModel, dt: float, tc_steps: float) -> None:
    m.opt.timestep = dt
    m.eq_solref[:, 0] = tc_steps * dt
    m.pair_solref[:, 0] = tc_steps * dt


def _advance(m: mujoco.MjModel, d: mujoco.MjData, steps: int) -> None:
    """`steps` MuJoCo steps; Diverged with the time of the first bad step."""
    state = np.empty(mujoco.mj_stateSize(m, STATE))
    mujoco.mj_getState(m, d, state, STATE)
    mujoco.mj_step(m, d, steps)
    if _healthy(d):
        return
    mujoco.mj_setState(m, d, state, STATE)
    for w in BAD:
        d.warning[w].number = 0
    start = d.time
    for _ in range(steps):
        start = d.time
        mujoco.mj_step(m, d)
        if not _healthy(d):
            break
    when = f"t = {start:.6g} s" + (" (in the run-in before the start)" if start < 0.0 else "")
    raise Diverged(f"MuJoCo became unstable (bad acceleration) at {when}", float(start))


def _healthy(d: mujoco.MjData) -> bool:
    return not any(d.warning[w].number for w in BAD) and bool(np.isfinite(d.qpos).all())


def _record(
    m: mujoco.MjModel, d: mujoco.MjData, model: Model, pos: np.ndarray, vel: np.ndarray, acc: np.ndarray
) -> None:
    """Pose, velocity and acceleration of each output body's frame at the current state."""
    mujoco.mj_forward(m, d)
    mujoco.mj_rnePostConstraint(m, d)
    _read(m, d, model, pos, vel, acc)


def _read(
    m: mujoco.MjModel, d: mujoco.MjData, model: Model, pos: np.ndarray, vel: np.ndarray, acc: np.ndarray
) -> None:
    """The outputs from d's computed kinematics, velocities and accelerations (cacc)."""
    six = np.empty(6)
    gx, gy = m.opt.gravity[:2]  # MuJoCo's accelerations carry the world's -gravity
    for k, site in enumerate(model.sites):
        pos[k, :2] = d.site_xpos[site][:2]
        pos[k, 2] = _evaluate(model.theta[k], model, d.qpos)
        mujoco.mj_objectVelocity(m, d, mujoco.mjtObj.mjOBJ_SITE, site, six, 0)
        vel[k] = six[3], six[4], six[2]
        mujoco.mj_objectAcceleration(m, d, mujoco.mjtObj.mjOBJ_SITE, site, six, 0)
        acc[k] = six[3] + gx, six[4] + gy, six[2]
