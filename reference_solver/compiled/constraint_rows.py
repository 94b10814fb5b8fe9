"""Every constraint row of the vocabulary in one uniform form, the form the kernels evaluate:

    C = [nothing | component x or y of vector A | A . B] + sum_k a_k q_k - constant - f(t)

where A and B are sums of signed terms (a point R + A u, a direction A u, a cam's profile point
R + A u(phi) or its tangent A u'(phi)). Each function mirrors one equation class of the plain path
(reference_solver.equations: joints, gears, cams, drivers) constraint row for constraint row.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

from scenarios import cams, drivers, gears, joints
from scenarios.bodies import Point, Vec2
from scenarios.motions import Motion
from scenarios.scenario import Constraint

NONLINEAR_NONE, COMPONENT_X, COMPONENT_Y, INNER = 0, 1, 2, 3
POINT, DIRECTION, PROFILE_POINT, PROFILE_TANGENT = 1, 2, 3, 4


class NotCompiled(TypeError):
    """A constraint or motion the compiled path has no kernel for (the plain path handles it)."""


@dataclass(frozen=True)
class Term:
    """sign * (a point, direction or profile vector fixed on `body`)."""

    kind: int
    body: str
    local: Vec2 = (0.0, 0.0)
    sign: float = 1.0
    contact: str | None = None
    """The cam contact of a profile term (whose profile the program takes from the scenario's cams)."""


@dataclass(frozen=True)
class ConstraintRowSpec:
    kind: int
    a: tuple[Term, ...] = ()
    b: tuple[Term, ...] = ()
    linear: tuple[tuple[str, int, float], ...] = ()
    """(body, coordinate 0/1/2, coefficient); ground terms are dropped when compiled."""
    constant: float = 0.0
    motion: Motion | None = None


def _point(p: Point, sign: float = 1.0) -> Term:
    return Term(POINT, p.body, p.local, sign)


def _difference(p: Point, q: Point) -> tuple[Term, Term]:
    return _point(p), _point(q, -1.0)


def _unit(v: Vec2) -> Vec2:
    norm = float(math.hypot(*v))
    return v[0] / norm, v[1] / norm


def _components(vector: tuple[Term, ...], motions: tuple[Motion | None, Motion | None] = (None, None)):  # type: ignore[no-untyped-def]
    return ConstraintRowSpec(COMPONENT_X, vector, motion=motions[0]), ConstraintRowSpec(
        COMPONENT_Y, vector, motion=motions[1]
    )


def _ground(j: joints.Ground) -> tuple[ConstraintRowSpec, ...]:
    return tuple(
        ConstraintRowSpec(NONLINEAR_NONE, linear=((j.body, k, 1.0),), constant=j.pose[k]) for k in range(3)
    )


def _revolute(j: joints.Revolute) -> tuple[ConstraintRowSpec, ...]:
    return _components(_difference(j.p_i, j.p_j))  # type: ignore[no-any-return]


def _prismatic(j: joints.Prismatic) -> tuple[ConstraintRowSpec, ...]:
    ax, ay = _unit(j.axis)
    angle = ConstraintRowSpec(
        NONLINEAR_NONE, linear=((j.p_i.body, 2, 1.0), (j.p_j.body, 2, -1.0)), constant=j.angle
    )
    normal = ConstraintRowSpec(INNER, (Term(DIRECTION, j.p_i.body, (-ay, ax)),), _difference(j.p_i, j.p_j))
    return angle, normal


def _revolute_revolute(j: joints.RevoluteRevolute) -> tuple[ConstraintRowSpec, ...]:
    d = _difference(j.p_i, j.p_j)
    return (ConstraintRowSpec(INNER, d, d, constant=j.length**2),)


def _gear_pair(g: gears.GearPair) -> tuple[ConstraintRowSpec, ...]:
    ri, rj = g.radius_i, (-g.radius_j if g.internal else g.radius_j)
    terms = ((g.gear_i, 2, ri), (g.gear_j, 2, rj), (g.carrier, 2, -(ri + rj)))
    constant = ri * g.theta0_i + rj * g.theta0_j - (ri + rj) * g.theta0_carrier
    return (ConstraintRowSpec(NONLINEAR_NONE, linear=terms, constant=constant),)


def _rack_pinion(g: gears.RackPinion) -> tuple[ConstraintRowSpec, ...]:
    axis = (Term(DIRECTION, g.rack.body, _unit(g.axis)),)
    turn = ((g.centre.body, 2, -g.radius), (g.rack.body, 2, g.radius))
    return (ConstraintRowSpec(INNER, axis, _difference(g.rack, g.centre), turn, constant=g.offset),)


def _profile(contact: cams.CamContact, kind: int, sign: float = 1.0) -> Term:
    return Term(kind, contact.cam, sign=sign, contact=contact.name)


def _knife_edge(c: cams.KnifeEdgeCam) -> tuple[ConstraintRowSpec, ...]:
    return _components((_profile(c, PROFILE_POINT), _point(c.tip, -1.0)))  # type: ignore[no-any-return]


def _roller(c: cams.RollerCam) -> tuple[ConstraintRowSpec, ...]:
    n = (_point(c.centre), _profile(c, PROFILE_POINT, -1.0))
    tangent = ConstraintRowSpec(INNER, n, (_profile(c, PROFILE_TANGENT),))
    return tangent, ConstraintRowSpec(INNER, n, n, constant=c.roller_radius**2)


def _flat_face(c: cams.FlatFaceCam) -> tuple[ConstraintRowSpec, ...]:
    h = (Term(DIRECTION, c.face.body, _unit(c.normal)),)
    tangent = ConstraintRowSpec(INNER, h, (_profile(c, PROFILE_TANGENT),))
    return tangent, ConstraintRowSpec(INNER, h, (_profile(c, PROFILE_POINT), _point(c.face, -1.0)))


COORDINATES = {"x": 0, "y": 1, "theta": 2}


def _absolute(d: drivers.AbsoluteDriver) -> tuple[ConstraintRowSpec, ...]:
    return (
        ConstraintRowSpec(
            NONLINEAR_NONE, linear=((d.body, COORDINATES[d.coordinate], 1.0),), motion=d.motion
        ),
    )


def _relative_rotation(d: drivers.RelativeRotationDriver) -> tuple[ConstraintRowSpec, ...]:
    terms = ((d.body_i, 2, 1.0), (d.body_j, 2, -1.0))
    return (ConstraintRowSpec(NONLINEAR_NONE, linear=terms, motion=d.motion),)


def _point_path(d: drivers.PointPathDriver) -> tuple[ConstraintRowSpec, ...]:
    return _components((_point(d.point),), (d.motion_x, d.motion_y))  # type: ignore[no-any-return]


def _relative_displacement(d: drivers.RelativeDisplacementDriver) -> tuple[ConstraintRowSpec, ...]:
    return _components(_difference(d.p_i, d.p_j), (d.motion_x, d.motion_y))  # type: ignore[no-any-return]


CONSTRAINT_ROWS: dict[type, Callable[..., tuple[ConstraintRowSpec, ...]]] = {
    joints.Ground: _ground,
    joints.Revolute: _revolute,
    joints.Prismatic: _prismatic,
    joints.RevoluteRevolute: _revolute_revolute,
    gears.GearPair: _gear_pair,
    gears.RackPinion: _rack_pinion,
    cams.KnifeEdgeCam: _knife_edge,
    cams.RollerCam: _roller,
    cams.FlatFaceCam: _flat_face,
    drivers.AbsoluteDriver: _absolute,
    drivers.RelativeRotationDriver: _relative_rotation,
    drivers.PointPathDriver: _point_path,
    drivers.RelativeDisplacementDriver: _relative_displacement,
}


def constraint_rows_of(constraint: Constraint) -> tuple[ConstraintRowSpec, ...]:
    """The constraint rows of one constraint, in the plain path's order."""
    try:
        return CONSTRAINT_ROWS[type(constraint)](constraint)
    except KeyError:
        raise NotCompiled(f"no compiled kernel for {type(constraint).__name__}") from None
