"""Plane vectors that carry their kinematics, so constraints are composed rather than derived by hand.

A KinematicVector v(q) holds its value, its Jacobian over a constraint's local columns, its time
derivative v_dot = v_q q_dot, and `acc`, the part of its second derivative that remains when the
accelerations are zero: v_ddot = v_q q_ddot + acc. A constraint row built from such vectors has
C_q = its Jacobian and Q_d = -(its own acc), the formulation's -(C_q q_dot)_q q_dot.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


def perp(v: np.ndarray) -> np.ndarray:
    """v turned by +90 degrees: A_theta u = perp(A u)."""
    return np.array([-v[1], v[0]])


def rotation(theta: float) -> np.ndarray:
    c, s = math.cos(theta), math.sin(theta)
    return np.array([[c, -s], [s, c]])


@dataclass(frozen=True)
class KinematicVector:
    value: np.ndarray
    jac: np.ndarray
    dot: np.ndarray
    acc: np.ndarray

    def __sub__(self, other: KinematicVector) -> KinematicVector:
        return KinematicVector(
            self.value - other.value, self.jac - other.jac, self.dot - other.dot, self.acc - other.acc
        )


@dataclass(frozen=True)
class ConstraintRow:
    """One scalar constraint row: value C, Jacobian over the local columns, and Q_d."""

    value: float
    jac: np.ndarray
    q_d: float


def body_vector(
    local: np.ndarray, pose: np.ndarray, rate: np.ndarray, col: int | None, width: int
) -> KinematicVector:
    """A direction fixed on a body, A u: it turns with the body's angle (column col + 2).

    `col` None means the ground: pose and rate are zero and there is no column.
    """
    au = rotation(pose[2]) @ local
    jac = np.zeros((2, width))
    if col is not None:
        jac[:, col + 2] = perp(au)
    return KinematicVector(au, jac, perp(au) * rate[2], -au * rate[2] ** 2)


def translate(v: KinematicVector, pose: np.ndarray, rate: np.ndarray, col: int | None) -> KinematicVector:
    """R + v for a vector v expressed on the body whose coordinates start at `col`."""
    jac = v.jac
    if col is not None:
        jac = jac.copy()
        jac[0, col] += 1.0
        jac[1, col + 1] += 1.0
    return KinematicVector(pose[:2] + v.value, jac, rate[:2] + v.dot, v.acc)


def body_point(
    local: np.ndarray, pose: np.ndarray, rate: np.ndarray, col: int | None, width: int
) -> KinematicVector:
    """A point fixed on a body, R + A u, the body's coordinates in columns col..col+2."""
    return translate(body_vector(local, pose, rate, col, width), pose, rate, col)


def profile_vector(
    derivatives: np.ndarray,
    pose: np.ndarray,
    rate: np.ndarray,
    phi_rate: float,
    col: int | None,
    phi_col: int,
    width: int,
) -> KinematicVector:
    """A u(phi) on a body (angle in column col + 2, phi in phi_col). `derivatives` holds u, u', u''
    as its first rows; pass the rows from u' on to get the profile's tangent A u'(phi)."""
    a = rotation(pose[2])
    au, adu, addu = a @ derivatives[0], a @ derivatives[1], a @ derivatives[2]
    jac = np.zeros((2, width))
    if col is not None:
        jac[:, col + 2] = perp(au)
    jac[:, phi_col] = adu
    w = rate[2]
    dot = perp(au) * w + adu * phi_rate
    acc = -au * w * w + 2.0 * perp(adu) * w * phi_rate + addu * phi_rate * phi_rate
    return KinematicVector(au, jac, dot, acc)


def inner(a: KinematicVector, b: KinematicVector) -> ConstraintRow:
    """The constraint row a . b."""
    value = float(a.value @ b.value)
    jac = a.jac.T @ b.value + b.jac.T @ a.value
    acc = float(a.acc @ b.value + 2.0 * (a.dot @ b.dot) + a.value @ b.acc)
    return ConstraintRow(value, jac, -acc)


def components(v: KinematicVector) -> tuple[ConstraintRow, ConstraintRow]:
    """The two constraint rows v_x and v_y."""
    return tuple(ConstraintRow(float(v.value[k]), v.jac[k], -float(v.acc[k])) for k in (0, 1))  # type: ignore[return-value]
