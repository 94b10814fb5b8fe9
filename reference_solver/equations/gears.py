"""Equations of the gears: a spur pair on a carrier, and rack and pinion."""

from __future__ import annotations

import numpy as np

from reference_solver.equation import Equation
from reference_solver.kinematic_vectors import ConstraintRow, inner
from reference_solver.layout import Layout
from scenarios.gears import GearPair, RackPinion
from scenarios.geometry import unit


class GearPairEquation(Equation):
    """r_i (th_i - th_i0) + s r_j (th_j - th_j0) - (r_i + s r_j)(th_k - th_k0) = 0, s = -1 internal."""

    def __init__(self, gear: GearPair, layout: Layout):
        super().__init__(gear.name, layout, (gear.gear_i, gear.gear_j, gear.carrier))
        self.gear = gear
        self.labels = (f"{gear.name}.mesh",)
        self.powers = (1,)

    def constraint_rows(self, q: np.ndarray, qd: np.ndarray, t: float) -> tuple[ConstraintRow, ...]:
        g = self.gear
        ri, rj = g.radius_i, (-g.radius_j if g.internal else g.radius_j)
        terms: dict[tuple[str, int], float] = {}
        for body, coefficient in ((g.gear_i, ri), (g.gear_j, rj), (g.carrier, -(ri + rj))):
            terms[(body, 2)] = terms.get((body, 2), 0.0) + coefficient
        constant = ri * g.theta0_i + rj * g.theta0_j - (ri + rj) * g.theta0_carrier
        return (self.linear_constraint_row(q, terms, constant),)


class RackPinionEquation(Equation):
    """u . (r_P - r_c) - radius (th_pinion - th_rack) - offset = 0."""

    def __init__(self, gear: RackPinion, layout: Layout):
        super().__init__(gear.name, layout, (gear.centre.body, gear.rack.body))
        self.gear = gear
        self.axis = unit(gear.axis)
        self.labels = (f"{gear.name}.mesh",)
        self.powers = (1,)

    def constraint_rows(self, q: np.ndarray, qd: np.ndarray, t: float) -> tuple[ConstraintRow, ...]:
        g = self.gear
        u = self.direction(q, qd, g.rack.body, self.axis)
        travel = inner(u, self.point(q, qd, g.rack) - self.point(q, qd, g.centre))
        turn = self.linear_constraint_row(
            q, {(g.centre.body, 2): g.radius, (g.rack.body, 2): -g.radius}, -g.offset
        )
        return (ConstraintRow(travel.value - turn.value, travel.jac - turn.jac, travel.q_d),)
