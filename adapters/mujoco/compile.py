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
from adapters.mujoco.dynamics import rate_velocities
from adapters.mujoco.forces import force_map
from adapters.mujoco.laws import Law, laws
from adapters.mujoco.mjcf import Physics, mjcf
from adapters.mujoco.model import Model, evaluate
from adapters.mujoco.scale import Scale, clock_armature
from adapters.mujoco.stepping import advance
from adapters.mujoco.tree import Tree, angle
from scenarios.bodies import Pose
from scenarios.scenario import Scenario


def compile_model(scenario: Scenario, tree: Tree, physics: Physics, run_in: int, scale: Scale) -> Model:
    """Compile the model for `tree` and find its start at t = 0, kept as the key 'start': the
    mechanism is assembled at t = -run_in steps (stepping back from t = 0 so that Newton stays on the
    assembled branch; preloaded contacts settled) and run in to t = 0, so
    that the soft constraints start in their own steady state rather than in a transient."""
    found = laws(scenario, tree)
    cams = cam_pairs(scenario.cams, tree, physics.cam_pieces)
    m = mujoco.MjModel.from_xml_string(mjcf(scenario, tree, found, cams, physics))
    d = mujoco.MjData(m)
    clocks = clocks_at(m, found, 0.0)
    assemble(m, d, clocks, scale)
    for t in -physics.timestep * np.arange(1, run_in + 1):
        clocks = clocks_at(m, found, float(t))
        assemble(m, d, clocks, scale)
    if m.npair:
        settle(m, d, clocks)
    if scenario.analysis == "dynamic":
        sites = [mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_SITE, b.name) for b in scenario.bodies]
        rate_velocities(m, d, sites, np.array([b.rate for b in scenario.bodies], dtype=float))
    if run_in:
        d.time = -run_in * physics.timestep
        advance(m, d, run_in)
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
        forces=force_map(scenario, tree, found, m),
    )


def clocks_at(m: mujoco.MjModel, found: list[Law], t: float) -> dict[int, tuple[float, float]]:
    """Each clock's dof and its (qpos, qvel) at time t."""
    clocks = [law.clock for law in found if law.clock is not None]
    return {int(m.jnt_dofadr[m.joint(c.joint).id]): c.at(t) for c in clocks}


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


def clock_armatures(scenario: Scenario, tree: Tree, model: Model, scale: Scale) -> dict[str, float]:
    """Each clock's armature, sized by the inertia it drives at the assembled start."""
    names = [law.clock.joint for law in laws(scenario, tree) if law.clock is not None]
    m = model.model
    d = mujoco.MjData(m)
    d.qpos[:], d.qvel[:] = model.qpos0, model.qvel0
    mujoco.mj_forward(m, d)
    dofs = [model.joint_ids[name] for name in names]
    speeds = clock_velocities(m, d, dofs, scale)
    return {name: clock_armature(m, d, qvel, dofs) for name, qvel in zip(names, speeds, strict=True)}


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
