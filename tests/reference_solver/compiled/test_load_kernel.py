"""The compiled force elements (compiled.load_program, compiled.load_kernel) against the plain ones
(dynamics.loads) on random states, every element type, and gravity; plain Loads is itself checked
against finite differences in tests/reference_solver/dynamics/test_force_elements.py."""

from __future__ import annotations

import numpy as np
import pytest

from reference_solver.compiled.load_kernel import loads as load_kernel
from reference_solver.compiled.load_program import compile_loads
from tests.support.force_elements import CASES, STATES, loads


@pytest.mark.parametrize("case", [*CASES, "all"])
def test_compiled_loads_are_the_plain_loads(case: str) -> None:
    forces = tuple(f for c in CASES.values() for f in c) if case == "all" else CASES[case]
    plain = loads(forces, gravity=(0.3, -9.81))
    program = compile_loads(plain.forces, plain.layout, plain.gravity)
    qe, points, totals = np.empty(6), np.empty((2, 6)), np.empty(3)
    for q, qd, t in STATES:
        load_kernel(program.ints, program.reals, program.gravity, q, qd, t, qe, points, totals)
        expected = plain(q, qd, t)
        scale = max(1.0, float(np.max(np.abs(expected.generalized))))
        np.testing.assert_allclose(qe, expected.generalized, rtol=0, atol=1e-12 * scale)
        wanted = (expected.potential, expected.applied_power, expected.dissipation)
        np.testing.assert_allclose(totals, wanted, rtol=1e-12, atol=1e-12)
