"""ALI3-P's projections of the rates onto the constraint manifold: after each step, q' onto
C_q q' = -C_t and q'' onto C_q q'' = Q_d, in the metric P of the step's tangent (P = M + h/2 D +
h^2/4 K; M alone where there are no force elements), so the correction is mass-orthogonal.

The published projection is one penalty step, W x = P x* + h^2/4 alpha C_q^T b with
W = P + h^2/4 alpha C_q^T C_q, which meets C_q x = b to about 1/(1 + PENALTY). Here its augmented
Lagrangian iteration continues (multipliers sigma += alpha (C_q x - b)) until the rates stop
changing, so the constraint holds to round-off where C_q has full rank, and in the least-squares
sense where it has not; the projected rates are the exact P-orthogonal projection.
"""

from __future__ import annotations

from typing import Protocol

import numpy as np

PROJECTION_STEPS = 30
SETTLED = 1e-15
STALLED = 1e-13
"""The projection stops when an iteration moves the rates by less than SETTLED relative to their
largest, or, below STALLED, no longer halves its move (round-off)."""


class Stepper(Protocol):
    """What a projection needs of the time step: h, alpha, P x and W^-1 x."""

    h: float
    alpha: np.ndarray

    def weigh(self, x: np.ndarray) -> np.ndarray: ...

    def solve(self, rhs: np.ndarray) -> np.ndarray: ...


def project(
    stepper: Stepper, jac: np.ndarray, rates: np.ndarray, target: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """The P-orthogonal projection x of `rates` onto C_q x = target, and its multipliers mu:
    P (x - rates) + C_q^T mu = 0."""
    factor = stepper.h * stepper.h / 4
    x = rates.copy()
    sigma = np.zeros(target.size)
    gap = jac @ x - target
    scale = max(float(np.max(np.abs(rates))), 1e-300)
    previous = np.inf
    for _ in range(PROJECTION_STEPS):
        residual = stepper.weigh(x - rates) + factor * (jac.T @ (stepper.alpha * gap + sigma))
        move = stepper.solve(residual)
        x -= move
        gap = jac @ x - target
        sigma += stepper.alpha * gap
        size = float(np.max(np.abs(move))) / scale
        if size <= SETTLED or (size < STALLED and size > 0.5 * previous):
            break
        previous = size
    return x, factor * sigma
