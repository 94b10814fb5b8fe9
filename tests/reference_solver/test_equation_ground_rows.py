"""The equations' base (reference_solver.equation) on a constraint between two ground points: no
moving body, so no column, and rows that are constants of the ground's geometry."""

from __future__ import annotations

import dataclasses

import numpy as np

import scenarios
from reference_solver.system import ConstraintSystem
from scenarios import GROUND, Point, Revolute


def test_a_joint_between_two_ground_points_has_constant_rows_and_no_column() -> None:
    """A revolute joining the ground's (0, 0) and (0.3, 0.4), added to the four-bar: its rows are
    r_i - r_j = (-0.3, -0.4) at any q and t, and zero in C_q (no column: an empty integer index)."""
    base = scenarios.build("four_bar")
    joint = Revolute("grounded", Point(GROUND, (0.0, 0.0)), Point(GROUND, (0.3, 0.4)))
    system = ConstraintSystem(dataclasses.replace(base, joints=(*base.joints, joint)))
    index = next(k for k, eq in enumerate(system.equations) if eq.name == "grounded")
    assert system.equations[index].columns.size == 0
    first = sum(eq.size for eq in system.equations[:index])
    rows = slice(first, first + 2)
    rng = np.random.default_rng(41)
    for _ in range(3):
        q, t = rng.normal(size=system.unknowns), float(rng.uniform(0, 1))
        np.testing.assert_allclose(system.residual(q, t)[rows], [-0.3, -0.4], rtol=0, atol=1e-15)
        np.testing.assert_array_equal(system.jacobian(q, t)[rows], 0.0)
