"""What keeps MuJoCo's cam contact honest: a sharp enough knife edge, a preload sized by the load,
and a run that stops when the contact opens.

MuJoCo holds a follower on its cam with a spring through a soft, one-sided contact. Three ways for
that model to stop being the cam while still producing a smooth trajectory:
- the knife edge is the 90 degree corner of a box: past a 45 degree pressure angle the disc touches
  the box's side and the follower silently becomes flat-faced. The largest pressure angle is
  computed from the profile and the scenario refused past MAX_EDGE_PRESSURE_ANGLE;
- a fixed preload is overcome by the follower's inertia at speed: the preload is PRELOAD_MARGIN
  times the follower's largest inertial force (its mass times the profile's largest acceleration at
  the drive's speed), never below PRELOAD_FLOOR (a light preload chatters on the soft contact);
- the contact can still open (a preload set by hand, a transient): `check_contacts` ends the run as
  `failed` at the first grid time whose contact row is missing or carries no force (a faceted cam's
  follower may instead be off by less than its polygon's sagitta: it hops off convex vertices).
"""

from __future__ import annotations

import math

import mujoco
import numpy as np

from adapters.base import EngineFailure
from adapters.mujoco.assembly import closest_contacts
from adapters.mujoco.cam_tip import tip_radius
from adapters.mujoco.pairs import FOLLOWER, PairTable, margins
from scenarios.cam_profiles import EccentricDisc
from scenarios.cams import CamContact, FlatFaceCam, KnifeEdgeCam, RollerCam, follower_body
from scenarios.drivers import AbsoluteDriver
from scenarios.scenario import Scenario

EDGE_CORNER = math.pi / 2
"""The knife edge's included angle: the corner of a box."""
EDGE_MARGIN = math.radians(5.0)
MAX_EDGE_PRESSURE_ANGLE = (math.pi - EDGE_CORNER) / 2 - EDGE_MARGIN
"""Past (pi - corner) / 2 = 45 degrees the disc's normal leaves the corner's normal cone and the
contact moves onto a side; 5 degrees are kept in hand (40 degrees)."""
PRELOAD_MARGIN = 200.0
"""The preload is this many times the follower's largest inertial force. The soft contact lets its
follower go long before the preload is used up: at the settings rule's step, cam_roller (0.2 kg)
lost its contact at 5 to 20 times its inertial force (60 to 300 rad/s), the knife edge and the flat
face at 100 times (300 rad/s); at 200 times every disc cam holds from 30 to 3000 rad/s with the same
error whatever the speed (6.2e-5 of the length for the knife edge and flat face, 9.8e-5 for the
roller), since the step, the time constant and the preload all scale with it."""
PRELOAD_FLOOR = 100.0
"""N. Below about 10 N the soft contact chatters (velocity error 1e-4, acceleration 0.5 relative at
0.6 N on cam_roller); 100 N is the measured quiet preload at moderate speed."""
SAMPLES = 2048
"""Profile angles sampled over one turn for the largest pressure angle and acceleration."""
FORCE_FLOOR = 1e-9
"""A contact force at or below this fraction of the preload counts as zero."""


def pressure_angle(contact: KnifeEdgeCam) -> float:
    """The largest angle between the profile's normal at the tip and the line from the cam's centre
    to the tip, atan(|d'| / d) over one turn: the angle the wedge must accept for a follower whose
    line of motion passes through the cam's centre (the MuJoCo wedge points along that line)."""
    phis = np.linspace(0.0, 2.0 * math.pi, SAMPLES, endpoint=False)
    radii = np.array([contact.profile.radii(float(p))[:2] for p in phis])
    return float(np.max(np.arctan2(np.abs(radii[:, 1]), radii[:, 0])))


def knife_edge_reason(contact: CamContact) -> str | None:
    """Why the box-corner knife edge would not stay a knife edge on this profile, if it would not (a
    knife edge on a faceted profile is a sphere, adapters.mujoco.cam_tip: it has no corner)."""
    if not isinstance(contact, KnifeEdgeCam) or tip_radius(contact) > 0.0:
        return None
    psi = pressure_angle(contact)
    if psi <= MAX_EDGE_PRESSURE_ANGLE:
        return None
    return (
        f"cam '{contact.name}': the pressure angle reaches {math.degrees(psi):.1f} deg, past the "
        f"{math.degrees(MAX_EDGE_PRESSURE_ANGLE):.0f} deg a knife edge made of a box corner takes "
        f"(a {math.degrees(EDGE_CORNER):.0f} deg corner touches with its side past "
        f"{math.degrees((math.pi - EDGE_CORNER) / 2):.0f} deg and the follower becomes flat-faced)"
    )


def _lift_radius(contact: CamContact, disc: EccentricDisc) -> EccentricDisc | None:
    """The circle whose polar radius is the follower's lift: the disc itself for a knife edge, the
    disc grown by the roller for a roller; None for a flat face (its lift is e cos, below)."""
    if isinstance(contact, RollerCam):
        return EccentricDisc(disc.radius + contact.roller_radius, disc.eccentricity)
    if isinstance(contact, FlatFaceCam):
        return None
    return disc


def largest_acceleration(scenario: Scenario, contact: CamContact) -> float:
    """The follower's largest acceleration along its line over the scenario's grid: d'' w^2 + d' a
    with w, a the cam's driven rate and angular acceleration (0 when the cam is not driven alone)."""
    disc = contact.profile
    if not isinstance(disc, EccentricDisc):
        return 0.0
    rate, spin = _cam_rates(scenario, contact.cam)
    lift = _lift_radius(contact, disc)
    phis = np.linspace(0.0, 2.0 * math.pi, SAMPLES, endpoint=False)
    if lift is None:
        first, second = disc.eccentricity * np.ones_like(phis), disc.eccentricity * np.ones_like(phis)
    else:
        derivatives = np.array([lift.radii(float(p))[1:3] for p in phis])
        first, second = np.abs(derivatives[:, 0]), np.abs(derivatives[:, 1])
    return float(np.max(second) * rate**2 + np.max(first) * spin)


def _cam_rates(scenario: Scenario, cam: str) -> tuple[float, float]:
    """The cam's largest |rate| and |angular acceleration| over the grid from its own driver."""
    times = scenario.times()
    for driver in scenario.drivers:
        if isinstance(driver, AbsoluteDriver) and driver.body == cam and driver.coordinate == "theta":
            rate = max(abs(driver.motion.df(t)) for t in times)
            return rate, max(abs(driver.motion.ddf(t)) for t in times)
    return 0.0, 0.0


def preload(scenario: Scenario) -> float:
    """The follower preload (N): PRELOAD_MARGIN times the largest inertial force over the cams,
    at least PRELOAD_FLOOR."""
    forces = [scenario.body(follower_body(c)).mass * largest_acceleration(scenario, c) for c in scenario.cams]
    return max(PRELOAD_FLOOR, PRELOAD_MARGIN * max(forces, default=0.0))


def check_contacts(
    m: mujoco.MjModel,
    d: mujoco.MjData,
    load: float,
    hops: dict[int, float] | None = None,
    table: PairTable | None = None,
) -> None:
    """Raise a `failed` EngineFailure if some cam (its pairs: one, or one per facet) has no contact
    row or no force now (after a forward pass at the current state). `hops`: per faceted cam (pair
    group), the gap it may show instead (`hop_allowances`): a follower is thrown off each convex
    vertex, where its velocity turns and its contact's compression is released, and lands within a
    few steps. `table`: PairTable.of(m), where the caller has it already."""
    table = PairTable.of(m) if table is None else table
    count = len(table.followers)
    forces = np.zeros(count)
    found = np.zeros(count, dtype=bool)
    for _, group, address, _ in table.contacts(d):
        if address >= 0:
            found[group] = True
            forces[group] += d.efc_force[address]
    for group in range(count):
        if found[group] and forces[group] > FORCE_FLOOR * load:
            continue
        allowed = (hops or {}).get(group)
        gap = _gap(m, d, table, group, allowed) if allowed else None
        if gap is not None:
            continue
        follower = m.geom(table.followers[group]).name
        what = "no contact row" if not found[group] else f"force {forces[group]:.3g} N"
        raise EngineFailure(
            f"contact lost: cam '{follower.removesuffix(FOLLOWER)}' at t = {d.time:.6g} s "
            f"({what}; the follower left the cam, preload {load:.3g} N)",
            float(d.time),
        )


def hop_allowances(m: mujoco.MjModel, qpos: np.ndarray, sagittas: dict[int, float]) -> dict[int, float]:
    """Per faceted cam: the larger of its polygon's sagitta and its contact's static penetration at
    the start, the gap a hop off a vertex may open (both are errors the model has anyway)."""
    d = mujoco.MjData(m)
    d.qpos[:] = qpos
    mujoco.mj_forward(m, d)
    closest = closest_contacts(m, d)
    depth = {group: max(0.0, -float(d.contact[i].dist)) for group, i in closest.items()}
    return {group: max(sag, depth.get(group, 0.0)) for group, sag in sagittas.items()}


def _gap(m: mujoco.MjModel, d: mujoco.MjData, table: PairTable, group: int, within: float) -> float | None:
    """The least distance between this cam's (`group`'s) follower and its cam geoms if below `within`."""
    try:
        with margins(m, table, within, [group]):
            mujoco.mj_collision(m, d)
            dists = [dist for _, k, _, dist in table.contacts(d) if k == group]
    finally:
        mujoco.mj_forward(m, d)
    return min(dists) if dists and min(dists) <= within else None
