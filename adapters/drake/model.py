"""The Drake diagram of a planned scenario: a discrete MultibodyPlant with the SAP solver (the only
one that takes loop and coupler constraints), its PD drive fed by a TrajectorySource, and the
consistent start found on the plant's own kinematics.

Every body's Drake frame is the scenario's body frame, so body poses read from the plant are the
canonical trajectory's positions without a change of frame.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from pydrake.math import RigidTransform, RotationMatrix
from pydrake.multibody.plant import AddMultibodyPlant, MultibodyPlant, MultibodyPlantConfig
from pydrake.multibody.tree import (
    FixedOffsetFrame,
    JacobianWrtVariable,
    PdControllerGains,
    PrismaticJoint,
    RevoluteJoint,
    RevoluteSpring,
    RotationalInertia,
    SpatialInertia,
    WeldJoint,
)
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import TrajectorySource
from pydrake.trajectories import PiecewisePolynomial

from adapters.base import Singular
from adapters.drake.loads import Loads, add_springs
from adapters.drake.tree import Plan
from scenarios.bodies import GROUND, Pose
from scenarios.scenario import Scenario

Z = np.array([0.0, 0.0, 1.0])
ANCHOR = "ground:anchor"
NEWTON_TOL = 1e-13
"""Residual bound of the start's assembly, relative to the characteristic length."""


@dataclass(frozen=True)
class Knobs:
    """The plant's accuracy knobs (adapters.drake.settings): step, PD gains, the drive's lead (its
    target sampled at t + lead * h)."""

    dt: float
    kp: float
    kd: float
    lead: float


@dataclass
class Diagram:
    """The built diagram and what the run reads from it."""

    diagram: Any
    plant: MultibodyPlant
    bodies: dict[str, Any]
    drive_joint: Any
    drive_map: tuple[float, float]
    """(a, b): the driven body coordinate = a * joint coordinate + b."""
    dt: float


def _transform(pose: Pose) -> RigidTransform:
    return RigidTransform(RotationMatrix.MakeZRotation(pose[2]), [pose[0], pose[1], 0.0])


def build_diagram(scenario: Scenario, plan: Plan, knobs: Knobs, span: tuple[float, float]) -> Diagram:
    """The plant, its constraints and drive, with the drive's target tabulated over `span` (scenario
    times) on the simulator's clock, which reads 0 at span[0]: Drake samples a discrete plant at
    whole multiples of its step from 0, and at none before 0."""
    builder = DiagramBuilder()
    config = MultibodyPlantConfig(time_step=knobs.dt, discrete_contact_approximation="sap")
    plant, _ = AddMultibodyPlant(config, builder)
    plant.mutable_gravity_field().set_gravity_vector([*scenario.gravity, 0.0])
    bodies: dict[str, Any] = {GROUND: plant.world_body()}
    for body in scenario.bodies:
        moment = max(body.inertia, 1e-12)  # Ixx = Iyy = Izz: a valid rigid inertia in 3-D
        inertia = SpatialInertia.MakeFromCentralInertia(
            body.mass, [0.0, 0.0, 0.0], RotationalInertia(moment, moment, moment)
        )
        bodies[body.name] = plant.AddRigidBody(body.name, inertia)
    joints: dict[str, Any] = {}
    for edge in plan.edges:
        parent = plant.AddFrame(
            FixedOffsetFrame(
                f"{edge.name}:parent", bodies[edge.parent].body_frame(), _transform(edge.parent_frame)
            )
        )
        child = plant.AddFrame(
            FixedOffsetFrame(
                f"{edge.name}:child", bodies[edge.child].body_frame(), _transform(edge.child_frame)
            )
        )
        if edge.kind == "revolute":
            damping = sum(t.damping for t in plan.torsions if t.edge == edge.name)
            joints[edge.name] = plant.AddJoint(RevoluteJoint(edge.name, parent, child, Z, damping))
        elif edge.kind == "prismatic":
            axis = [edge.axis[0], edge.axis[1], 0.0]
            joints[edge.name] = plant.AddJoint(PrismaticJoint(edge.name, parent, child, axis))
        else:
            joints[edge.name] = plant.AddJoint(WeldJoint(edge.name, parent, child, RigidTransform()))
    ends = {GROUND: _anchor(plant) if any(GROUND in (b.p_i.body, b.p_j.body) for b in plan.balls) else None}
    for ball in plan.balls:
        first, second = (bodies if p.body != GROUND else ends for p in (ball.p_i, ball.p_j))
        plant.AddBallConstraint(
            first[ball.p_i.body], [*ball.p_i.local, 0.0], second[ball.p_j.body], [*ball.p_j.local, 0.0]
        )
    for coupler in plan.couplers:
        # Drake's law: q0 = ratio * q1 + offset, joint0 the secondary
        plant.AddCouplerConstraint(
            joints[coupler.secondary], joints[coupler.primary], coupler.ratio, coupler.offset
        )
    add_springs(plant, bodies, plan.springs)
    for torsion in plan.torsions:
        plant.AddForceElement(RevoluteSpring(joints[torsion.edge], torsion.q0, torsion.stiffness))
    drive_joint = None
    if plan.driver is not None:
        drive_edge = next(e for e in plan.edges if e.child == plan.driver.body)
        drive_joint = joints[drive_edge.name]
        actuator = plant.AddJointActuator(f"{plan.driver.name}:actuator", drive_joint)
        actuator.set_controller_gains(PdControllerGains(p=knobs.kp, d=knobs.kd))
    plant.Finalize()
    built = Diagram(None, plant, bodies, drive_joint, (1.0, 0.0), knobs.dt)
    if drive_joint is not None:
        built.drive_map = _drive_map(built, plan)
        source = builder.AddSystem(TrajectorySource(_target(built, plan, knobs, span)))
        builder.Connect(
            source.get_output_port(), plant.get_desired_state_input_port(drive_joint.model_instance())
        )
    if plan.loads:
        loads = builder.AddSystem(Loads(bodies, plan.loads, span[0]))
        builder.Connect(loads.get_output_port(), plant.get_applied_spatial_force_input_port())
    built.diagram = builder.Build()
    return built


def _anchor(plant: MultibodyPlant) -> Any:
    """A body welded to the world at its origin, standing for the ground in ball constraints: Drake
    1.51's SAP step crashes (segmentation fault) on a ball constraint whose end is the world body."""
    anchor = plant.AddRigidBody(ANCHOR, SpatialInertia.SolidSphereWithMass(1.0, 1.0))
    plant.WeldFrames(plant.world_frame(), anchor.body_frame())
    return anchor


def body_coordinate(built: Diagram, context: Any, body: str, coordinate: str) -> float:
    """A body's x, y or theta in the plant's `context`."""
    pose = built.plant.EvalBodyPoseInWorld(context, built.bodies[body])
    if coordinate == "theta":
        rotation = pose.rotation().matrix()
        return float(np.arctan2(rotation[1, 0], rotation[0, 0]))
    return float(pose.translation()[0 if coordinate == "x" else 1])


def _drive_map(built: Diagram, plan: Plan) -> tuple[float, float]:
    """(a, b) with the driven coordinate = a q + b, read from the plant at q = 0 and q = 1 (the driven
    body's joint is on the ground, so the map is affine; an angle is unwrapped by the caller)."""
    context = built.plant.CreateDefaultContext()
    joint, driver = built.drive_joint, plan.driver
    assert driver is not None
    values = []
    for q in (0.0, 1.0 if driver.coordinate != "theta" else 0.5):
        joint.set_default_positions([q])
        built.plant.SetDefaultContext(context)
        values.append(body_coordinate(built, context, driver.body, driver.coordinate))
    joint.set_default_positions([0.0])
    step = 1.0 if driver.coordinate != "theta" else 0.5
    a = (values[1] - values[0]) / step
    if abs(a) < 1e-9:
        raise Singular(f"driver '{driver.name}': its coordinate does not move with its joint")
    if driver.coordinate == "theta":
        a = float(np.sign(a))
    return a, values[0]


def _target(built: Diagram, plan: Plan, knobs: Knobs, span: tuple[float, float]) -> PiecewisePolynomial:
    """The drive's desired (q, v) at t + lead * dt, tabulated at every step as cubic Hermite pieces
    (exact at the plant's sample times, where the discrete PD reads it)."""
    a, b = built.drive_map
    assert plan.driver is not None
    motion = plan.driver.motion
    n = int(np.ceil((span[1] - span[0]) / knobs.dt)) + 3
    times = np.arange(n) * knobs.dt  # the simulator's clock, which starts at 0 at span[0]
    ahead = span[0] + times + knobs.lead * knobs.dt
    q = np.array([(motion.f(t) - b) / a for t in ahead])
    v = np.array([motion.df(t) / a for t in ahead])
    acc = np.array([motion.ddf(t) / a for t in ahead])
    return PiecewisePolynomial.CubicHermite(times, np.vstack([q, v]), np.vstack([v, acc]))


def assemble(built: Diagram, scenario: Scenario, plan: Plan, context: Any, t0: float) -> None:
    """Positions and velocities in `context` on the loops and the drive at t0: Newton from the bodies'
    guesses on the plant's own point positions and Jacobians; Singular where it does not converge."""
    plant = built.plant
    q = np.zeros(plant.num_positions())
    for edge in plan.edges:
        if edge.kind != "fixed":
            joint = plant.GetJointByName(edge.name)
            q[joint.position_start()] = edge.q0
    length = scenario.characteristic_length
    for _ in range(50):
        plant.SetPositions(context, q)
        residual, jacobian = _rows(built, plan, context, t0)
        if np.max(np.abs(residual), initial=0.0) < NEWTON_TOL * length:
            break
        q = q - np.linalg.lstsq(jacobian, residual, rcond=None)[0]
    else:
        raise Singular(f"the start does not assemble (loop residual {np.max(np.abs(residual)):.3g})")
    if plan.driver is None:
        plant.SetVelocities(context, free_rates(built, scenario, context, jacobian))
        return
    rhs = np.zeros(len(residual))
    rhs[-1] = plan.driver.motion.df(t0)
    plant.SetVelocities(context, np.linalg.lstsq(jacobian, rhs, rcond=None)[0])


def free_rates(built: Diagram, scenario: Scenario, context: Any, rows: np.ndarray) -> np.ndarray:
    """The joint rates of a free start: those that best give the bodies' start rates (vx, vy,
    omega), projected onto the closure rows' velocity constraints in the kinetic-energy norm (as
    the native solver projects them)."""
    plant, world = built.plant, built.plant.world_frame()
    jac: list[np.ndarray] = []
    rates: list[float] = []
    for body in scenario.bodies:
        spatial = plant.CalcJacobianSpatialVelocity(
            context, JacobianWrtVariable.kV, built.bodies[body.name].body_frame(), np.zeros(3), world, world
        )
        jac.append(spatial[[3, 4, 2]])
        rates.extend(body.rate)
    v = np.linalg.lstsq(np.vstack(jac), np.asarray(rates, dtype=np.float64), rcond=None)[0]
    if len(rows):
        m_inv_g = np.linalg.solve(plant.CalcMassMatrix(context), rows.T)
        v = v - m_inv_g @ np.linalg.lstsq(rows @ m_inv_g, rows @ v, rcond=None)[0]
    return np.asarray(v)


def _rows(built: Diagram, plan: Plan, context: Any, t: float) -> tuple[np.ndarray, np.ndarray]:
    """The closure rows (ball gaps in x, y; coupler laws) and the drive row, with their Jacobians."""
    plant, world = built.plant, built.plant.world_frame()
    values: list[float] = []
    rows: list[np.ndarray] = []
    for ball in plan.balls:
        ends = []
        for point in (ball.p_i, ball.p_j):
            frame = built.bodies[point.body].body_frame()
            local = np.array([*point.local, 0.0])
            position = plant.CalcPointsPositions(context, frame, local, world).ravel()
            jac = plant.CalcJacobianTranslationalVelocity(
                context, JacobianWrtVariable.kQDot, frame, local, world, world
            )
            ends.append((position, jac))
        values += list(ends[0][0][:2] - ends[1][0][:2])
        rows += list(ends[0][1][:2] - ends[1][1][:2])
    q = plant.GetPositions(context)
    for coupler in plan.couplers:
        primary = plant.GetJointByName(coupler.primary).position_start()
        secondary = plant.GetJointByName(coupler.secondary).position_start()
        row = np.zeros(len(q))
        row[secondary], row[primary] = 1.0, -coupler.ratio
        values.append(float(row @ q) - coupler.offset)
        rows.append(row)
    driver = plan.driver
    if driver is not None:
        a, b = built.drive_map
        row = np.zeros(len(q))
        row[built.drive_joint.position_start()] = a
        values.append(a * q[built.drive_joint.position_start()] + b - driver.motion.f(t))
        rows.append(row)
    return np.array(values), np.array(rows).reshape(len(values), len(q))
