"""A small second-order forward algebra for constraint rows.

A `Quantity` is a vector function g of the unknowns z (joint coordinates and cam contact parameters)
carried with its Jacobian dg/dz, its rate g' = (dg/dz) z' and its drift: the second time derivative
with z'' = 0. A row g(z) = f(t) then gives
    position      (dg/dz) dz = f - g           (Newton)
    velocity      (dg/dz) z' = f'
    acceleration  (dg/dz) z'' = f'' - drift.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

TURN = np.array([[0.0, -1.0], [1.0, 0.0]])
"""The planar rotation by +90 degrees."""


@dataclass(frozen=True)
class Quantity:
    val: np.ndarray
    jac: np.ndarray
    rate: np.ndarray
    drift: np.ndarray

    @classmethod
    def constant(cls, value: np.ndarray | float, n: int) -> Quantity:
        v = np.atleast_1d(np.asarray(value, dtype=float))
        zero = np.zeros_like(v)
        return cls(v, np.zeros((v.size, n)), zero, zero)

    def __add__(self, other: Quantity) -> Quantity:
        return Quantity(
            self.val + other.val, self.jac + other.jac, self.rate + other.rate, self.drift + other.drift
        )

    def __sub__(self, other: Quantity) -> Quantity:
        return Quantity(
            self.val - other.val, self.jac - other.jac, self.rate - other.rate, self.drift - other.drift
        )

    def __mul__(self, k: float) -> Quantity:
        return Quantity(self.val * k, self.jac * k, self.rate * k, self.drift * k)


def inner(a: Quantity, b: Quantity) -> Quantity:
    """The scalar product a . b of two planar vectors."""
    av, bv = a.val, b.val
    return Quantity(
        np.array([av[0] * bv[0] + av[1] * bv[1]]),
        (av @ b.jac + bv @ a.jac)[None, :],
        np.array([a.rate @ bv + av @ b.rate]),
        np.array([a.drift @ bv + 2.0 * (a.rate @ b.rate) + av @ b.drift]),
    )


def _turn(angle: float, v: np.ndarray) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])


def turned(theta: Quantity, u: np.ndarray) -> Quantity:
    """A(theta) u for a body angle theta and a constant vector u given in the body's frame."""
    w = _turn(float(theta.val[0]), u)
    tw = np.array([-w[1], w[0]])
    omega = float(theta.rate[0])
    return Quantity(w, tw[:, None] * theta.jac, tw * omega, tw * float(theta.drift[0]) - w * omega**2)


def rotated(theta: Quantity, local: Quantity) -> Quantity:
    """A(theta) u for a body angle theta and a vector u(z) given in the body's frame."""
    angle, omega = float(theta.val[0]), float(theta.rate[0])
    c, s = math.cos(angle), math.sin(angle)
    a = np.array([[c, -s], [s, c]])
    w = a @ local.val
    tw = np.array([-w[1], w[0]])
    w_rate = a @ local.rate
    return Quantity(
        w,
        tw[:, None] * theta.jac + a @ local.jac,
        tw * omega + w_rate,
        tw * float(theta.drift[0])
        - w * omega**2
        + 2.0 * omega * np.array([-w_rate[1], w_rate[0]])
        + a @ local.drift,
    )


def along(curve: np.ndarray, column: int, phi_rate: float, n: int) -> Quantity:
    """A local vector u(phi) on a curve, from rows u, u', u'' of `curve`; phi is unknown `column`."""
    jac = np.zeros((2, n))
    jac[:, column] = curve[1]
    return Quantity(curve[0].copy(), jac, curve[1] * phi_rate, curve[2] * phi_rate**2)


def stack(quantities: list[Quantity]) -> Quantity:
    """One Quantity holding every row of `quantities`."""
    if len(quantities) == 1:
        return quantities[0]
    return Quantity(
        np.concatenate([q.val for q in quantities]),
        np.concatenate([q.jac for q in quantities]),
        np.concatenate([q.rate for q in quantities]),
        np.concatenate([q.drift for q in quantities]),
    )
