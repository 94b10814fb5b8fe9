"""Compiling a scenario into a MuJoCo model with its consistent start: MJCF from the planned tree,
the start assembled on MuJoCo's own constraint rows, the bodies' poses there, the clocks' armatures
and the cam followers' preload springs sized from it."""

from __future__ import annotations

import math

import mujoco
import numpy as np

from adapters.base import Unsupported
from adapters.mujoco.assembly import assemble, clock_velocities, contact_slopes, settle
from adapters.mujoco.cams import CamPair, cam_pairs
from adapters.mujoco.controls import controls
from adapters.mujoco.dynamics import rate_velocities
from adapters.mujoco.forces import force_map
from adapters.mujoco.laws import Clock, Law, laws
from adapters.mujoco.mjcf import Physics, mjcf
from adapters.mujoco.model import Model, evaluate
from adapters.mujoco.pairs import PairTable
from adapters.mujoco.scale import Scale, clock_armature
from adapters.mujoco.simulation import advance
from adapters.mujoco.tree import Tree, angle
from adapters.mujoco.weights import weigh
from scenarios.bodies import Pose
from scenarios.scenario import Scenario


def compile_model(
    scenario: Scenario, tree: Tree, physics: Physics, run_in: int, scale: Scale, linear: bool = False
) -> Model:
    """Compile the model for `tree` and find its start at t = 0, kept as the key 'start': the
    mechanism is assembled at t = -run_in steps (stepping back from t = 0 so that Newton stays on the
    assembled branch; preloaded contacts settled) and run in to t = 0 (the steered clocks under
    their controls), so that the soft constraints start in their own steady state rather than in a
    transient. The clocks keep the state the run-in leaves them in: under a first-order integrator
    a harmonic clock is then off its law by its phase error (7e-6 m on the slider drive), but in
    step with the joints it drives; set back onto its law alone it would violate its drive equality
    at t = 0 and start the transient the run-in is there to avoid. The regulariser is scaled before
    either (adapters.mujoco.weights): scaled after, the start would carry the old model's offset.
    `linear`: every law linear in its clock (the sizing model, see clock_armatures)."""
    found = laws(scenario, tree, physics.steer)
    if linear:
        found = [law.linearised() for law in found]
    cams = cam_pairs(scenario.cams, tree, physics.cam_pieces)
    m = mujoco.MjModel.from_xml_string(mjcf(scenario, tree, found, cams, physics))
    weigh(m, physics.invweight)
    d = mujoco.MjData(m)
    table = PairTable.of(m)
    clocks = clocks_at(m, found, 0.0)
    assemble(m, d, clocks, scale, table=table)
    for t in -physics.timestep * np.arange(1, run_in + 1):
        clocks = clocks_at(m, found, float(t))
        assemble(m, d, clocks, scale, table=table)
    if cams:
        settle(m, d, clocks, table=table)
    if scenario.analysis == "dynamic":
        sites = [mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_SITE, b.name) for b in scenario.bodies]
        rate_velocities(m, d, sites, np.array([b.rate for b in scenario.bodies], dtype=float))
    if run_in:
        d.time = -run_in * physics.timestep
        with controls(m, d, physics.loads.motors, clock_dofs(m, found), before=0.0):
            advance(m, d, run_in)
        d.time = 0.0
    start = (d.qpos.copy(), d.qvel.copy())
    outputs = scenario.output_bodies
    return Model(
        write=lambda: mjcf(scenario, tree, found, cams, physics, start),
        model=m,
        qpos0=d.qpos.copy(),
        qvel0=d.qvel.copy(),
        dt=physics.timestep,
        solref=physics.solref,
        contact_solref=physics.contact_solref or physics.solref,
        bodies=outputs,
        sites=[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_SITE, b) for b in outputs],
        theta=[angle(tree, b) for b in outputs],
        joint_ids={m.joint(j).name: m.jnt_dofadr[j] for j in range(m.njnt)},
        clocks=clock_dofs(m, found),
        forces=force_map(scenario, tree, found, m),
        pairs=table,
    )


def clock_dofs(m: mujoco.MjModel, found: list[Law]) -> dict[int, Clock]:
    """Each clock by its dof."""
    return {int(m.jnt_dofadr[m.joint(law.clock.joint).id]): law.clock for law in found if law.clock}


def clocks_at(m: mujoco.MjModel, found: list[Law], t: float) -> dict[int, tuple[float, float]]:
    """Each clock's dof and its (qpos, qvel) at time t."""
    return {dof: clock.at(t) for dof, clock in clock_dofs(m, found).items()}


def assembled_poses(scenario: Scenario, tree: Tree, model: Model) -> dict[str, Pose]:
    """Every body's frame pose at the assembled start (angles continuous with the tree's)."""
    m = model.model
    d = mujoco.MjData(m)
    d.qpos[:] = model.qpos0
    mujoco.mj_kinematics(m, d)
    poses: dict[str, Pose] = {}
    for body in scenario.body_names:
        x, y = d.site_xpos[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_SITE, body)][:2]
        poses[body] = (float(x), float(y), evaluate(angle(tree, body), model, model.qpos0))
    return poses


def clock_armatures(
    scenario: Scenario, tree: Tree, model: Model, scale: Scale, steer: bool = False
) -> dict[str, float]:
    """Each clock's armature, sized by the inertia it drives at the assembled start. `model` is the
    sizing model (compile_model's `linear`), where a unit clock rate moves each driven coordinate at
    unit rate; a polynomial's clock runs at unit rate and moves its coordinate at P'(t), so the
    inertia it drives is that times the largest P'(t)^2 over the horizon."""
    found = [law for law in laws(scenario, tree, steer) if law.clock is not None]
    names = [law.clock.joint for law in found if law.clock is not None]
    m = model.model
    d = mujoco.MjData(m)
    d.qpos[:], d.qvel[:] = model.qpos0, model.qvel0
    mujoco.mj_forward(m, d)
    dofs = [model.joint_ids[name] for name in names]
    speeds = clock_velocities(m, d, dofs, scale)
    gains = [_gain(law.powers, scenario.t_end) for law in found]
    return {
        name: clock_armature(m, d, qvel * gain, dofs)
        for name, qvel, gain in zip(names, speeds, gains, strict=True)
    }


def _gain(powers: tuple[float, ...], t_end: float) -> float:
    """The largest |P'(t)| over [0, t_end] (sampled finely; 1 for a law linear in its clock)."""
    if powers == (1.0,):
        return 1.0
    slope = np.polynomial.Polynomial([k * p for k, p in enumerate(powers, start=1)])
    return max(float(np.abs(slope(np.linspace(0.0, t_end, 1001))).max()), 1e-300)


def follower_springs(
    scenario: Scenario, model: Model, tree: Tree, preload: float, scale: Scale, pieces: int
) -> dict[str, tuple[float, float]]:
    """A follower spring per cam pushing with `preload` into the contact at the start; it stiffens
    by 10 % over a characteristic length."""
    if not scenario.cams:
        return {}
    m = model.model
    d = mujoco.MjData(m)
    d.qpos[:], d.qvel[:] = model.qpos0, model.qvel0
    slopes = contact_slopes(m, d, scale)
    pairs: list[CamPair] = cam_pairs(scenario.cams, tree, pieces)
    springs = {}
    stiffness = preload / (10.0 * scenario.characteristic_length)
    for index, pair in enumerate(pairs):
        dof = model.joint_ids[pair.spring_joint]
        slope = slopes.get(index)
        if slope is None or slope[dof] == 0.0:
            raise Unsupported(f"cam '{pair.name}': the follower's joint does not move it off the cam")
        springs[pair.spring_joint] = (stiffness, -math.copysign(preload / stiffness, slope[dof]))
    return springs
