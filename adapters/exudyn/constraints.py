"""Constraints that Exudyn has no element for, written as residual, Jacobian and time derivative of
the scenario's own equations (formulation.md), for Exudyn's `ObjectConnectorCoordinateVector` with
constraint and Jacobian user functions.

Each constraint names the bodies whose coordinates (x, y, theta) it reads, in order, how many
extra unknowns (a cam's contact parameter phi) follow them, and its `size`, how many constraint rows
it has. `evaluate(poses, extra, t)` returns the residual C, one Jacobian block (size x 3) per body
(the ground's is ignored by the caller), the block of the extra unknowns (size x extra) and C_t.
Exudyn calls these a few times per step, so they are written in scalar Python, not numpy: a call
costs a few microseconds.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Protocol

from scenarios.bodies import GROUND, Point
from scenarios.cam_profiles import Profile
from scenarios.cams import FlatFaceCam, KnifeEdgeCam, RollerCam
from scenarios.drivers import PointPathDriver, RelativeDisplacementDriver
from scenarios.gears import RackPinion
from scenarios.motions import Motion

Rows = list[list[float]]
Evaluation = tuple[list[float], list[Rows], Rows, list[float]]
Vec = tuple[float, float]


class UserConstraint(Protocol):
    @property
    def name(self) -> str: ...
    @property
    def bodies(self) -> tuple[str, ...]: ...
    @property
    def extra(self) -> int: ...
    @property
    def size(self) -> int: ...

    def evaluate(self, poses: Sequence[Sequence[float]], extra: Sequence[float], t: float) -> Evaluation: ...


def _dot(a: Vec, b: Vec) -> float:
    return a[0] * b[0] + a[1] * b[1]


def _turn(theta: float, v: Vec) -> tuple[Vec, Vec]:
    """A(theta) v and dA/dtheta v."""
    c, s = math.cos(theta), math.sin(theta)
    return (c * v[0] - s * v[1], s * v[0] + c * v[1]), (-s * v[0] - c * v[1], c * v[0] - s * v[1])


def _point(pose: Sequence[float], local: Vec) -> tuple[Vec, Vec]:
    """A body-fixed point in global axes and its derivative in theta (d/dx, d/dy are the identity)."""
    (ax, ay), turned = _turn(pose[2], local)
    return (pose[0] + ax, pose[1] + ay), turned


def _translation(sign: float, d_theta: Vec) -> Rows:
    """The (2 x 3) Jacobian of +-(a body point) in (x, y, theta)."""
    return [[sign, 0.0, sign * d_theta[0]], [0.0, sign, sign * d_theta[1]]]


@dataclass(frozen=True)
class _Surface:
    """A polar cam profile u(phi) = d(phi) (cos phi, sin phi) on the cam body."""

    profile: Profile

    def at(self, pose: Sequence[float], phi: float) -> tuple[Vec, Vec, Vec, Vec, Vec]:
        """Global contact point r, dr/dtheta_cam, tangent t = dr/dphi, dt/dtheta_cam, dt/dphi."""
        d0, d1, d2, _ = self.profile.radii(phi)
        c, s = math.cos(phi), math.sin(phi)
        u0 = (d0 * c, d0 * s)
        u1 = (d1 * c - d0 * s, d1 * s + d0 * c)
        u2 = ((d2 - d0) * c - 2 * d1 * s, (d2 - d0) * s + 2 * d1 * c)
        r, r_theta = _point(pose, u0)
        tangent, tangent_theta = _turn(pose[2], u1)
        tangent_phi, _ = _turn(pose[2], u2)
        return r, r_theta, tangent, tangent_theta, tangent_phi


@dataclass(frozen=True)
class _CamContact:
    """What every cam contact holds: its name, (cam, follower), the cam's surface, and its one extra
    unknown (the contact parameter phi) beside two rows."""

    name: str
    bodies: tuple[str, ...]
    surface: _Surface
    extra: int = field(default=1, kw_only=True)
    size: int = field(default=2, kw_only=True)


@dataclass(frozen=True)
class KnifeEdgeContact(_CamContact):
    """r_cam(phi) - r_tip = 0."""

    tip: Vec

    def evaluate(self, poses: Sequence[Sequence[float]], extra: Sequence[float], t: float) -> Evaluation:
        r, r_theta, tangent, _, _ = self.surface.at(poses[0], extra[0])
        tip, tip_theta = _point(poses[1], self.tip)
        residual = [r[0] - tip[0], r[1] - tip[1]]
        blocks = [_translation(1.0, r_theta), _translation(-1.0, tip_theta)]
        return residual, blocks, [[tangent[0]], [tangent[1]]], [0.0, 0.0]


@dataclass(frozen=True)
class RollerContact(_CamContact):
    """n.t = 0 and n.n - r^2 = 0 with n = r_centre - r_cam(phi)."""

    centre: Vec
    radius: float

    def evaluate(self, poses: Sequence[Sequence[float]], extra: Sequence[float], t: float) -> Evaluation:
        r, r_theta, tan, tan_theta, tan_phi = self.surface.at(poses[0], extra[0])
        c, c_theta = _point(poses[1], self.centre)
        n = (c[0] - r[0], c[1] - r[1])
        residual = [_dot(n, tan), _dot(n, n) - self.radius**2]
        cam = [
            [-tan[0], -tan[1], -_dot(tan, r_theta) + _dot(n, tan_theta)],
            [-2 * n[0], -2 * n[1], -2 * _dot(n, r_theta)],
        ]
        follower = [[tan[0], tan[1], _dot(tan, c_theta)], [2 * n[0], 2 * n[1], 2 * _dot(n, c_theta)]]
        phi = [[-_dot(tan, tan) + _dot(n, tan_phi)], [-2 * _dot(n, tan)]]
        return residual, [cam, follower], phi, [0.0, 0.0]


@dataclass(frozen=True)
class FlatFaceContact(_CamContact):
    """h.t = 0 and h.(r_cam(phi) - r_face) = 0, h the face's unit normal on the follower."""

    face: Vec
    normal: Vec

    def evaluate(self, poses: Sequence[Sequence[float]], extra: Sequence[float], t: float) -> Evaluation:
        r, r_theta, tan, tan_theta, tan_phi = self.surface.at(poses[0], extra[0])
        q, q_theta = _point(poses[1], self.face)
        h, h_theta = _turn(poses[1][2], self.normal)
        d = (r[0] - q[0], r[1] - q[1])
        residual = [_dot(h, tan), _dot(h, d)]
        cam = [[0.0, 0.0, _dot(h, tan_theta)], [h[0], h[1], _dot(h, r_theta)]]
        follower = [[0.0, 0.0, _dot(tan, h_theta)], [-h[0], -h[1], _dot(d, h_theta) - _dot(h, q_theta)]]
        phi = [[_dot(h, tan_phi)], [_dot(h, tan)]]
        return residual, [cam, follower], phi, [0.0, 0.0]


@dataclass(frozen=True)
class RackPinionMesh:
    """u.(r_P - r_c) - radius (th_pinion - th_rack) - offset = 0, u the rack's unit axis."""

    name: str
    bodies: tuple[str, ...]  # (pinion, rack)
    centre: Vec
    pitch_point: Vec
    axis: Vec
    radius: float
    offset: float
    extra: int = 0
    size: int = 1

    def evaluate(self, poses: Sequence[Sequence[float]], extra: Sequence[float], t: float) -> Evaluation:
        c, c_theta = _point(poses[0], self.centre)
        p, p_theta = _point(poses[1], self.pitch_point)
        u, u_theta = _turn(poses[1][2], self.axis)
        d = (p[0] - c[0], p[1] - c[1])
        residual = [_dot(u, d) - self.radius * (poses[0][2] - poses[1][2]) - self.offset]
        pinion = [[-u[0], -u[1], -_dot(u, c_theta) - self.radius]]
        rack = [[u[0], u[1], _dot(d, u_theta) + _dot(u, p_theta) + self.radius]]
        return residual, [pinion, rack], [[]], [0.0]


@dataclass(frozen=True)
class PointDisplacement:
    """r_i^P - r_j^P - (fx(t), fy(t)) = 0 in global axes; body j may be the ground (a path driver)."""

    name: str
    bodies: tuple[str, ...]
    points: tuple[Vec, Vec]
    motions: tuple[Motion, Motion]
    extra: int = 0
    size: int = 2

    def evaluate(self, poses: Sequence[Sequence[float]], extra: Sequence[float], t: float) -> Evaluation:
        ri, ri_theta = _point(poses[0], self.points[0])
        rj, rj_theta = _point(poses[1], self.points[1])
        fx, fy = (m.f(t) for m in self.motions)
        residual = [ri[0] - rj[0] - fx, ri[1] - rj[1] - fy]
        blocks = [_translation(1.0, ri_theta), _translation(-1.0, rj_theta)]
        return residual, blocks, [[], []], [-m.df(t) for m in self.motions]


def user_constraint(item: object) -> UserConstraint | None:
    """The user-function form of a scenario constraint, or None when it has none here."""
    if isinstance(item, KnifeEdgeCam):
        return KnifeEdgeContact(item.name, (item.cam, item.tip.body), _Surface(item.profile), item.tip.local)
    if isinstance(item, RollerCam):
        bodies = (item.cam, item.centre.body)
        return RollerContact(item.name, bodies, _Surface(item.profile), item.centre.local, item.roller_radius)
    if isinstance(item, FlatFaceCam):
        bodies = (item.cam, item.face.body)
        return FlatFaceContact(item.name, bodies, _Surface(item.profile), item.face.local, _unit(item.normal))
    if isinstance(item, RackPinion):
        bodies = (item.centre.body, item.rack.body)
        axis = _unit(item.axis)
        return RackPinionMesh(
            item.name, bodies, item.centre.local, item.rack.local, axis, item.radius, item.offset
        )
    if isinstance(item, PointPathDriver):
        return _displacement(item.name, item.point, Point(GROUND), (item.motion_x, item.motion_y))
    if isinstance(item, RelativeDisplacementDriver):
        return _displacement(item.name, item.p_i, item.p_j, (item.motion_x, item.motion_y))
    return None


def _unit(v: Vec) -> Vec:
    norm = math.hypot(*v)
    return (v[0] / norm, v[1] / norm)


def _displacement(name: str, p_i: Point, p_j: Point, motions: tuple[Motion, Motion]) -> PointDisplacement:
    return PointDisplacement(name, (p_i.body, p_j.body), (p_i.local, p_j.local), motions)
