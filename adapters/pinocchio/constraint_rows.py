"""Loop-closure, gear, cam and driver constraint rows written with Pinocchio's frame placements,
frame Jacobians (LOCAL_WORLD_ALIGNED, x and y rows only: the out-of-plane rows are dropped) and
classical frame accelerations, on the unknowns z = [q ; phi] (joint coordinates, then one parameter
per cam contact).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from adapters.pinocchio.model import PinModel, frame_jacobian
from adapters.pinocchio.quantity import TURN, Quantity, along, inner, rotated, stack, turned
from scenarios.bodies import GROUND, Point
from scenarios.cam_profiles import profile_point
from scenarios.cams import CamContact, FlatFaceCam, KnifeEdgeCam, RollerCam
from scenarios.drivers import (
    AbsoluteDriver,
    Driver,
    PointPathDriver,
    RelativeDisplacementDriver,
    RelativeRotationDriver,
)
from scenarios.gears import GearPair, RackPinion
from scenarios.joints import Ground, Prismatic, Revolute, RevoluteRevolute
from scenarios.motions import Motion
from scenarios.scenario import Scenario

LWA = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED
ZERO1, ZERO2 = np.zeros(1), np.zeros(2)
"""Shared zero rates and drifts (Quantity arrays are never changed in place)."""


class Snapshot:
    """Pinocchio's kinematics at one state, read as Quantities on z = [q ; phi]."""

    def __init__(self, pm: PinModel, data: pin.Data, state: tuple[np.ndarray, ...], cams: int) -> None:
        q, v, phi, phi_rate = state
        self.pm, self.data, self.q, self.v = pm, data, q, v
        self.phi, self.phi_rate, self.nq = phi, phi_rate, pm.model.nq
        self.n = self.nq + cams
        self._points: dict[Point, Quantity] = {}
        self._angles: dict[str, Quantity] = {}
        self.moving = bool(v.any() or phi_rate.any())
        pin.forwardKinematics(pm.model, data, q, v, pm.zero_v)
        pin.computeJointJacobians(pm.model, data)
        pin.updateFramePlacements(pm.model, data)

    def point(self, point: Point) -> Quantity:
        """Global position of a point fixed on a body, with derivatives."""
        known = self._points.get(point)
        if known is not None:
            return known
        model, data, fid = self.pm.model, self.data, self.pm.frame_id[point]
        jac = np.zeros((2, self.n))
        jac[:, : self.nq] = frame_jacobian(model, data, fid)[:2]
        if self.moving:
            drift = pin.getFrameClassicalAcceleration(model, data, fid, LWA).linear[:2].copy()
            rate = jac[:, : self.nq] @ self.v
        else:
            drift = rate = ZERO2
        known = Quantity(data.oMf[fid].translation[:2].copy(), jac, rate, drift)
        self._points[point] = known
        return known

    def angle(self, body: str) -> Quantity:
        """A body's angle (0 for the ground); its drift is zero: every joint turns about z."""
        known = self._angles.get(body)
        if known is not None:
            return known
        if body == GROUND:
            known = Quantity.constant(0.0, self.n)
        else:
            jac = np.zeros((1, self.n))
            jac[0, : self.nq] = row = self.pm.angle_row[body]
            value = self.pm.angle(body, self.q)
            known = Quantity(np.array([value]), jac, np.array([row @ self.v]), ZERO1)
        self._angles[body] = known
        return known

    def direction(self, body: str, local: tuple[float, float] | np.ndarray) -> Quantity:
        """A body-fixed direction in global axes."""
        return turned(self.angle(body), np.asarray(local, dtype=float))

    def profile(self, cam: CamContact, k: int) -> tuple[Quantity, Quantity]:
        """The contact point r(phi) on the cam and the tangent there, for contact number k."""
        curve = profile_point(cam.profile, float(self.phi[k]))
        theta, rate = self.angle(cam.cam), float(self.phi_rate[k])
        column = self.nq + k
        point = self.point(Point(cam.cam)) + rotated(theta, along(curve, column, rate, self.n))
        return point, rotated(theta, along(curve[1:], column, rate, self.n))


def _joint_rows(item: object, s: Snapshot, contacts: dict[str, int]) -> list[Quantity]:
    """The rows that close a loop through a joint, gear or cam contact (target zero)."""
    n = s.n
    if isinstance(item, Revolute):
        return [s.point(item.p_i) - s.point(item.p_j)]
    if isinstance(item, Prismatic):
        normal = s.direction(item.p_i.body, TURN @ np.asarray(item.axis))
        twist = s.angle(item.p_i.body) - s.angle(item.p_j.body) - Quantity.constant(item.angle, n)
        return [twist, inner(normal, s.point(item.p_i) - s.point(item.p_j))]
    if isinstance(item, RevoluteRevolute):
        gap = s.point(item.p_i) - s.point(item.p_j)
        return [inner(gap, gap) - Quantity.constant(item.length**2, n)]
    if isinstance(item, Ground):
        pose = s.point(Point(item.body))
        return [
            pose - Quantity.constant(np.asarray(item.pose[:2]), n),
            s.angle(item.body) - Quantity.constant(item.pose[2], n),
        ]
    if isinstance(item, GearPair):
        sign = -1.0 if item.internal else 1.0
        ri, rj = item.radius_i, sign * item.radius_j
        law = s.angle(item.gear_i) * ri + s.angle(item.gear_j) * rj - s.angle(item.carrier) * (ri + rj)
        c = ri * item.theta0_i + rj * item.theta0_j - (ri + rj) * item.theta0_carrier
        return [law - Quantity.constant(c, n)]
    if isinstance(item, RackPinion):
        u = s.direction(item.rack.body, item.axis)
        turn = s.angle(item.centre.body) - s.angle(item.rack.body)
        travel = inner(u, s.point(item.rack) - s.point(item.centre))
        return [travel - turn * item.radius - Quantity.constant(item.offset, n)]
    if isinstance(item, KnifeEdgeCam):
        point, _ = s.profile(item, contacts[item.name])
        return [point - s.point(item.tip)]
    if isinstance(item, RollerCam):
        point, tangent = s.profile(item, contacts[item.name])
        gap = s.point(item.centre) - point
        return [inner(gap, tangent), inner(gap, gap) - Quantity.constant(item.roller_radius**2, n)]
    if isinstance(item, FlatFaceCam):
        point, tangent = s.profile(item, contacts[item.name])
        normal = s.direction(item.face.body, item.normal)
        return [inner(normal, tangent), inner(normal, point - s.point(item.face))]
    raise TypeError(f"no Pinocchio row for {type(item).__name__}")


def _driver_rows(driver: Driver, s: Snapshot) -> Quantity:
    if isinstance(driver, AbsoluteDriver):
        if driver.coordinate == "theta":
            return s.angle(driver.body)
        o = s.point(Point(driver.body))
        k = slice(0, 1) if driver.coordinate == "x" else slice(1, 2)
        return Quantity(o.val[k], o.jac[k], o.rate[k], o.drift[k])
    if isinstance(driver, RelativeRotationDriver):
        return s.angle(driver.body_i) - s.angle(driver.body_j)
    if isinstance(driver, PointPathDriver):
        return s.point(driver.point)
    return s.point(driver.p_i) - s.point(driver.p_j)


def force_labels(driver: Driver) -> tuple[str, ...]:
    """The trajectory columns of a driver's forces, as the canonical CSV names them: `<driver>.force`
    for a driver of one row, `<driver>.x.force` and `<driver>.y.force` for a point's two."""
    if isinstance(driver, AbsoluteDriver | RelativeRotationDriver):
        return (f"{driver.name}.force",)
    return (f"{driver.name}.x.force", f"{driver.name}.y.force")


def motions_of(driver: Driver) -> tuple[Motion, ...]:
    """The prescribed functions of a driver, one per row."""
    if isinstance(driver, PointPathDriver | RelativeDisplacementDriver):
        return (driver.motion_x, driver.motion_y)
    return (driver.motion,)


@dataclass(frozen=True)
class ConstraintRows:
    """The constraint rows of a scenario that the Pinocchio tree does not satisfy by construction: loop
    closures (target zero) first, then drivers (target f(t))."""

    closures: tuple[object, ...]
    drivers: tuple[Driver, ...]
    contacts: dict[str, int]
    motions: tuple[Motion, ...]

    @classmethod
    def of(cls, scenario: Scenario, pm: PinModel) -> ConstraintRows:
        items = {j.name: j for j in scenario.joints}
        contacts = {c.name: k for k, c in enumerate(scenario.cams)}
        motions = tuple(m for d in scenario.drivers for m in motions_of(d))
        return cls(tuple(items[name] for name in pm.tree.closures), scenario.drivers, contacts, motions)

    def loop_rows(self, s: Snapshot) -> list[Quantity]:
        return [row for item in self.closures for row in _joint_rows(item, s, self.contacts)]

    def drive_rows(self, s: Snapshot) -> Quantity:
        return stack([_driver_rows(d, s) for d in self.drivers])

    def evaluate(self, s: Snapshot) -> Quantity:
        """All rows stacked, loops first."""
        return stack([*self.loop_rows(s), *(_driver_rows(d, s) for d in self.drivers)])

    def targets(self, size: int, t: float, order: int) -> np.ndarray:
        """The right-hand side of `size` stacked rows: zeros for loops, then f, f' or f'' (order
        0, 1, 2) of each driver motion."""
        out = np.zeros(size)
        start = size - len(self.motions)
        for k, m in enumerate(self.motions):
            out[start + k] = (m.f, m.df, m.ddf)[order](t)
        return out
