"""The load program's rows (compiled.load_program) as its docstring lays them out: each element's kind and
its two bodies' first columns, -1 for the ground and for a force's missing second body; an element
with no kernel is named. The kernel (compiled.load_kernel) against the plain loads on the elements the
catalogue's cases leave out (a second body that is the ground or sits in column 0, a damper on a
ground point), and superposition: every element at once is the sum of each alone, in either order."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pytest

from reference_solver.compiled.constraint_rows import NotCompiled
from reference_solver.compiled.load_kernel import loads as load_kernel
from reference_solver.compiled.load_program import FORCE, ROTATIONAL, SPRING, TORQUE, compile_loads
from reference_solver.layout import Layout
from scenarios import GROUND, Constant, Harmonic, Point
from scenarios.forces import AppliedForce, AppliedTorque, Force, RotationalSpringDamper, SpringDamper
from tests.support.force_elements import CASES, STATES, loads

ELEMENTS: tuple[tuple[Force, tuple[int, int, int]], ...] = (
    (AppliedTorque("t", "b", Constant(1.0)), (TORQUE, 3, -1)),
    (AppliedTorque("t", "a", Constant(1.0), reaction="b"), (TORQUE, 0, 3)),
    (AppliedForce("f", Point("b", (0.1, 0.0)), Constant(1.0), Constant(2.0)), (FORCE, 3, -1)),
    (AppliedForce("f", Point("a", (0.1, 0.0)), Constant(1.0), Constant(2.0)), (FORCE, 0, -1)),
    (SpringDamper("s", Point(GROUND, (1.0, 0.0)), Point("b", (0.0, 0.1)), 5.0), (SPRING, -1, 3)),
    (SpringDamper("s", Point("b", (0.0, 0.1)), Point("a", (0.0, 0.0)), 5.0), (SPRING, 3, 0)),
    (RotationalSpringDamper("r", "a", GROUND, 2.0), (ROTATIONAL, 0, -1)),
    (RotationalSpringDamper("r", GROUND, "b", 2.0), (ROTATIONAL, -1, 3)),
)


def layout() -> Layout:
    """Bodies a and b, in columns 0 and 3."""
    return loads(()).layout


def test_each_row_names_its_bodies_first_columns_and_minus_one_for_none() -> None:
    where = layout()
    assert (where.body_column("a"), where.body_column("b")) == (0, 3)
    program = compile_loads(tuple(e for e, _ in ELEMENTS), where, np.zeros(6))
    np.testing.assert_array_equal(program.ints[:, :3], [row for _, row in ELEMENTS])


@dataclass(frozen=True)
class Gust:
    """A force element the kernel does not know."""

    name: str


def test_an_element_without_a_kernel_is_named() -> None:
    with pytest.raises(NotCompiled, match=r"^no compiled kernel for force element Gust$"):
        compile_loads((Gust("g"),), layout(), np.zeros(6))  # type: ignore[arg-type]


GROUNDED: dict[str, tuple[Force, ...]] = {
    "damped_spring_from_the_ground": (
        SpringDamper("s", Point(GROUND, (1.0, -0.5)), Point("b", (0.1, 0.2)), 80.0, 2.5, 0.4),
    ),
    "damped_spring_to_the_ground": (
        SpringDamper("s", Point("a", (0.1, 0.2)), Point(GROUND, (-0.5, 1.0)), 60.0, 1.5, 0.3),
    ),
    "torsion_to_the_ground": (RotationalSpringDamper("r", "b", GROUND, 7.0, 1.2, 0.3),),
    "torsion_from_the_ground": (RotationalSpringDamper("r", GROUND, "b", 6.0, 0.7, -0.4),),
    "torsion_onto_the_first_column": (RotationalSpringDamper("r", "b", "a", 5.0, 0.8, -0.2),),
    "torque_reacted_by_the_ground": (AppliedTorque("t", "a", Harmonic(1.0, 0.5, 3.0)),),
    "torque_reacted_by_the_first_column": (AppliedTorque("t", "b", Harmonic(-0.5, 0.7, 2.0), reaction="a"),),
}
"""Elements whose second body is the ground or sits in column 0 (the catalogue's cases have neither),
a torsion spring from the ground with stiffness (the catalogue's has damping only, so the ground's
angle went unread), the dampers with damping, so that a ground point's velocity counts."""


def run_kernel(
    forces: tuple[Force, ...], q: np.ndarray, qd: np.ndarray, t: float
) -> tuple[np.ndarray, np.ndarray]:
    """Q_e and (potential, applied power, dissipation) from the kernel, its scratch full of stale values."""
    plain = loads(forces, gravity=(0.3, -9.81))
    program = compile_loads(plain.forces, plain.layout, plain.gravity)
    qe, points, totals = np.empty(6), np.full((2, 6), 7.0), np.empty(3)
    load_kernel(program.ints, program.reals, program.gravity, q, qd, t, qe, points, totals)
    return qe, totals


@pytest.mark.parametrize("case", GROUNDED)
def test_elements_on_the_ground_or_the_first_column_are_the_plain_loads(case: str) -> None:
    plain = loads(GROUNDED[case], gravity=(0.3, -9.81))
    for q, qd, t in STATES:
        qe, totals = run_kernel(GROUNDED[case], q, qd, t)
        expected = plain(q, qd, t)
        scale = max(1.0, float(np.max(np.abs(expected.generalized))))
        np.testing.assert_allclose(qe, expected.generalized, rtol=0, atol=1e-12 * scale)
        wanted = (expected.potential, expected.applied_power, expected.dissipation)
        np.testing.assert_allclose(totals, wanted, rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("order", ["forward", "reversed"])
def test_elements_add_up(order: str) -> None:
    """Superposition: every element at once gives gravity plus the sum of each element's own Q_e
    over gravity, and the sums of their energies and powers, in either order of the elements."""
    every = tuple(f for c in (*CASES.values(), *GROUNDED.values()) for f in c)
    every = every if order == "forward" else every[::-1]
    for q, qd, t in STATES[:8]:
        gravity_qe, gravity_totals = run_kernel((), q, qd, t)
        alone = [run_kernel((f,), q, qd, t) for f in every]
        qe, totals = run_kernel(every, q, qd, t)
        np.testing.assert_allclose(
            qe, gravity_qe + sum(e - gravity_qe for e, _ in alone), rtol=1e-12, atol=1e-12
        )
        summed = gravity_totals + sum(s - gravity_totals for _, s in alone)
        np.testing.assert_allclose(totals, summed, rtol=1e-12, atol=1e-12)
