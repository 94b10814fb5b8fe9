"""The MJCF writer: a planned tree, its laws and cam pairs as one self-contained MuJoCo model file.

Bodies sit at the canonical body frames (a site named after each body marks it), hinges turn about
z, slides move in the plane, loops close with site-based `connect`, laws become `joint` equalities
(or a fixed tendon and a `tendon` equality when more than two joints take part), clocks are extra
rotors (a steered clock with a motor), cams are contact pairs (explicit ones, or a flat face on facets
by contype/conaffinity bits: adapters.mujoco.cams). Every number is written to full precision.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field

import numpy as np

from adapters.mujoco.cam_facets import DEFAULT_PIECES
from adapters.mujoco.cam_mjcf import cam_flags, cam_geoms, contact_pairs
from adapters.mujoco.cams import CamPair
from adapters.mujoco.equalities import equalities, num
from adapters.mujoco.laws import Law
from adapters.mujoco.loads import WORLD_SITE, Loads, site_name
from adapters.mujoco.tree import Tree, TreeJoint, rot
from scenarios.bodies import GROUND, Point
from scenarios.gears import GearPair, RackPinion
from scenarios.motions import Motion
from scenarios.scenario import Scenario

MASSLESS = 1e-9
"""A body without mass or inertia gets this fraction of the heaviest body's (MuJoCo needs both)."""
CLOCK_ARMATURE = 1.0e9
"""A clock's armature where the inertia it drives is not known (adapters.mujoco.scale sizes it)."""
CLOCK_INERTIA = 1.0
"""The clock body's own moment of inertia about its axis (its dof's inertia is this plus the armature)."""

SCALED_TOLERANCE, SCALED_ITERATIONS = 1e-30, 5
"""The solver's tolerance and iterations where the regulariser is scaled. MuJoCo's Newton solver
stops on a relative improvement of its cost, which the scaled regulariser makes tiny after one
iteration: at 1e-15 the constraint forces are off by 1e-5 to 1e-4 (slider-crank 6.2e-5, four-bar
7.8e-4); at 1e-30 they are at 1e-10 after two iterations. Without a cap on the iterations the
solver then goes on to its limit where nothing improves (Andrews' squeezer at 3.3 times the cost
per step, free dynamics at 0 ten times); five keep the cost and the forces."""


@dataclass(frozen=True)
class Physics:
    """MuJoCo options and constraint softness shared by every equality and contact."""

    integrator: str
    timestep: float
    solref: tuple[float, float]
    """The equalities' solref: (time constant, damping ratio), or (-stiffness, -damping) directly."""
    solimp: tuple[float, float, float, float, float]
    contact_solimp: tuple[float, float, float, float, float]
    contact_solref: tuple[float, float] | None = None
    """The cam contacts' solref (None: the equalities')."""
    invweight: float = 1.0
    """The factor on the compiled model's invweight0 (adapters.mujoco.weights)."""
    tolerance: float = 1e-15
    """The constraint solver's tolerance (and `iterations`, its limit); SCALED_TOLERANCE and
    SCALED_ITERATIONS where the regulariser is scaled (`invweight` below 1, adapters.mujoco.weights)."""
    iterations: int = 50
    springs: dict[str, tuple[float, float]] = field(default_factory=dict)
    """Preload springs: joint name -> (stiffness, springref)."""
    clock_armature: dict[str, float] = field(default_factory=dict)
    """Clock joint name -> armature (CLOCK_ARMATURE for a clock not listed or with nothing to drive)."""
    loads: Loads = field(default_factory=Loads)
    """Gravity, actuators, tendons and hinge springs of a dynamic scene (adapters.mujoco.loads)."""
    cam_pieces: int = DEFAULT_PIECES
    """Facets of a cam profile other than a disc (adapters.mujoco.cam_facets)."""
    steer: bool = False
    """Polynomial drives of degree 2 to 4 by steered clocks too, rather than through polycoef."""


def mjcf(
    scenario: Scenario,
    tree: Tree,
    laws: list[Law],
    cams: list[CamPair],
    physics: Physics,
    keyframe: tuple[np.ndarray, np.ndarray] | None = None,
) -> str:
    """The model as MJCF text; `keyframe` (qpos, qvel) is stored as the key named 'start'."""
    root = ET.Element("mujoco", model=scenario.name.replace("/", "_"))
    _options(root, scenario, physics, cams)
    world = ET.SubElement(root, "worldbody")
    ET.SubElement(world, "light", pos="0 0 2", dir="0 0 -1", directional="true")
    elements = {GROUND: world}
    for joint in tree.joints:
        elements[joint.child] = _body(elements[joint.parent], scenario, tree, joint.child, physics)
        if joint.kind != "fixed":
            elements[joint.child].insert(0, _joint(joint, physics))
    for law in laws:
        if law.clock is not None:
            _clock(world, law, physics)
    solref, solimp = num(*(physics.contact_solref or physics.solref)), num(*physics.contact_solimp)
    cam_geoms(elements, cams, solref, solimp)
    equalities(root, elements, tree, laws)
    _loads(root, elements, physics.loads)
    steered = [law for law in laws if law.clock is not None and law.clock.law is not None]
    _clock_motors(root, steered, physics)
    contact_pairs(root, cams, solref, solimp)
    if keyframe is not None:
        _keyframe(root, keyframe, physics, steered)
    ET.indent(root)
    return ET.tostring(root, encoding="unicode")


def _options(root: ET.Element, scenario: Scenario, physics: Physics, cams: list[CamPair]) -> None:
    """The compiler, the options (step, integrator, gravity, solver) and the defaults."""
    ET.SubElement(root, "compiler", angle="radian", autolimits="true")
    option = ET.SubElement(
        root,
        "option",
        timestep=num(physics.timestep),
        integrator=physics.integrator,
        gravity=num(*physics.loads.gravity, 0.0),
        tolerance=num(physics.tolerance if physics.invweight == 1.0 else SCALED_TOLERANCE),
        iterations=str(physics.iterations if physics.invweight == 1.0 else SCALED_ITERATIONS),
        jacobian="dense",
    )
    # A scene carries only what it needs: without cams there is nothing to collide.
    flags = {"autoreset": "disable"} if cams else {"autoreset": "disable", "contact": "disable"}
    ET.SubElement(option, "flag", {**flags, **cam_flags(cams)})
    default = ET.SubElement(root, "default")
    ET.SubElement(default, "geom", contype="0", conaffinity="0", rgba="0.6 0.7 0.8 1")
    ET.SubElement(default, "equality", solref=num(*physics.solref), solimp=num(*physics.solimp))
    ET.SubElement(default, "site", size=num(0.01 * scenario.characteristic_length), rgba="0.9 0.2 0.2 1")


def _joint(joint: TreeJoint, physics: Physics) -> ET.Element:
    """A tree joint (hinge or slide) with its spring, where the scenario or the laws give one."""
    attrs = {"name": joint.name, "type": joint.kind, "pos": num(*joint.anchor, 0.0)}
    attrs["axis"] = "0 0 1" if joint.kind == "hinge" else num(*joint.axis, 0.0)
    if joint.name in physics.springs:
        k, ref = physics.springs[joint.name]
        attrs.update(stiffness=num(k), springref=num(ref))
    hinge_springs = dict(physics.loads.hinge_springs)
    if joint.name in hinge_springs:
        spring = hinge_springs[joint.name]
        attrs.update(
            stiffness=num(spring.stiffness), damping=num(spring.damping), springref=num(spring.springref)
        )
    return ET.Element("joint", attrs)


def _clock(world: ET.Element, law: Law, physics: Physics) -> None:
    """A motion law's clock: a body on a hinge whose spring and armature make it turn as the law."""
    assert law.clock is not None
    armature = _armature(physics, law)
    clock = ET.SubElement(world, "body", name=law.clock.joint)
    ET.SubElement(clock, "inertial", pos="0 0 0", mass="1", diaginertia=" ".join([f"{CLOCK_INERTIA:g}"] * 3))
    ET.SubElement(
        clock,
        "joint",
        name=law.clock.joint,
        type="hinge",
        axis="0 0 1",
        armature=num(armature),
        stiffness=num(armature * law.clock.omega2),
    )


def _keyframe(
    root: ET.Element, keyframe: tuple[np.ndarray, np.ndarray], physics: Physics, steered: list[Law]
) -> None:
    """The start state as the key 'start', with the controls at t = 0 (constant ones hold
    throughout): the motors', then the steered clocks'."""
    key = ET.SubElement(ET.SubElement(root, "keyframe"), "key", name="start")
    key.set("qpos", num(*keyframe[0]))
    key.set("qvel", num(*keyframe[1]))
    ctrl = [motor.law.f(0.0) for motor in physics.loads.motors]
    ctrl += [_law_of(law).ddf(0.0) for law in steered]
    if ctrl:
        key.set("ctrl", num(*ctrl))


def _armature(physics: Physics, law: Law) -> float:
    assert law.clock is not None
    return physics.clock_armature.get(law.clock.joint, 0.0) or CLOCK_ARMATURE


def _law_of(law: Law) -> Motion:
    assert law.clock is not None and law.clock.law is not None
    return law.clock.law


def _clock_motors(root: ET.Element, steered: list[Law], physics: Physics) -> None:
    """A motor on each steered clock's joint, named after it, geared by the clock's inertia: its
    control is the clock's acceleration (adapters.mujoco.controls), well inside MuJoCo's bound on
    controls (1e10) where the torque would not be."""
    if not steered:
        return
    actuator = root.find("actuator")
    if actuator is None:
        actuator = ET.SubElement(root, "actuator")
    for law in steered:
        assert law.clock is not None
        gear = num(_armature(physics, law) + CLOCK_INERTIA)
        ET.SubElement(actuator, "motor", name=law.clock.joint, joint=law.clock.joint, gear=gear)


def _body(parent: ET.Element, scenario: Scenario, tree: Tree, name: str, physics: Physics) -> ET.Element:
    x, y, th = tree.poses[name]
    px, py, pth = (0.0, 0.0, 0.0) if parent.tag == "worldbody" else tree.poses[parent.get("name", "")]
    rel = rot(pth).T @ np.array([x - px, y - py])
    half = (th - pth) / 2.0
    element = ET.SubElement(
        parent,
        "body",
        name=name,
        pos=num(rel[0], rel[1], 0.0),
        quat=num(math.cos(half), 0.0, 0.0, math.sin(half)),
    )
    spec = scenario.body(name)
    inertia = spec.inertia or MASSLESS * max((b.inertia for b in scenario.bodies), default=0.0) or 1e-12
    mass = spec.mass or MASSLESS * max((b.mass for b in scenario.bodies), default=0.0) or 1e-9
    ET.SubElement(
        element, "inertial", pos="0 0 0", mass=num(mass), diaginertia=num(inertia, inertia, inertia)
    )
    ET.SubElement(element, "site", name=name, pos="0 0 0")
    _visual(element, scenario, name)
    return element


def _visual(body: ET.Element, scenario: Scenario, name: str) -> None:
    """Geometry for the viewer only (it neither collides nor adds mass)."""
    spec = scenario.body(name)
    radius = _pitch_radius(scenario, name)
    size = 0.05 * scenario.characteristic_length
    if spec.length > 0.0:
        half = spec.length / 2.0
        ET.SubElement(body, "geom", type="capsule", fromto=num(-half, 0, 0, half, 0, 0), size=num(half / 10))
    elif radius:
        ET.SubElement(body, "geom", type="cylinder", size=num(radius, size / 2), rgba="0.8 0.7 0.3 0.6")
    else:
        ET.SubElement(body, "geom", type="box", size=num(size, size, size / 2), rgba="0.3 0.5 0.8 1")


def _pitch_radius(scenario: Scenario, name: str) -> float:
    for joint in scenario.joints:
        if isinstance(joint, GearPair) and name in (joint.gear_i, joint.gear_j):
            return joint.radius_i if name == joint.gear_i else joint.radius_j
        if isinstance(joint, RackPinion) and joint.centre.body == name:
            return joint.radius
    return 0.0


def _loads(root: ET.Element, elements: dict[str, ET.Element], loads: Loads) -> None:
    """Sites, spatial tendons and motor actuators of the loads (their controls are set in data)."""
    if not (loads.motors or loads.tendons):
        return
    named = {site.get("name") for site in root.iter("site")}

    def site(p: Point) -> str:
        name = site_name(p)
        if name not in named:
            ET.SubElement(elements[p.body], "site", name=name, pos=num(*p.local, 0.0))
            named.add(name)
        return name

    site(Point(GROUND, (0.0, 0.0)))
    assert WORLD_SITE in named
    if loads.tendons:
        tendon = root.find("tendon")
        if tendon is None:
            tendon = ET.SubElement(root, "tendon")
        for spring in loads.tendons:
            spatial = ET.SubElement(
                tendon,
                "spatial",
                name=spring.name,
                stiffness=num(spring.stiffness),
                damping=num(spring.damping),
                springlength=num(spring.free_length),
            )
            ET.SubElement(spatial, "site", site=site(spring.p_i))
            ET.SubElement(spatial, "site", site=site(spring.p_j))
    if loads.motors:
        actuator = ET.SubElement(root, "actuator")
        for motor in loads.motors:
            ET.SubElement(
                actuator,
                "motor",
                name=motor.name,
                site=site(motor.site),
                refsite=motor.refsite,
                gear=num(*motor.gear),
            )
