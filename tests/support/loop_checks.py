"""What a compiled time loop's run must hold, checked against definitions computed with the plain
constraint system and dense algebra."""

from __future__ import annotations

import numpy as np

from reference_solver.compiled import path
from reference_solver.system import ConstraintSystem
from scenarios import Scenario


def completed_run(scenario, grid, tolerance=1e-12, max_iterations=25):  # type: ignore[no-untyped-def]
    run = path.run(scenario, np.asarray(grid, dtype=float), tolerance, max_iterations)
    assert run.event == "ok" and run.index == len(grid), run.event
    assert run.analysis is not None
    return run.analysis


def dense_scaled_rcond_1(system: ConstraintSystem, q: np.ndarray, t: float) -> float:
    """1 / (|A|_1 |A^-1|_1) of the scaled C_q, by dense inversion."""
    a = system.scaled_jacobian(system.jacobian(q, t))
    return float(1.0 / (np.linalg.norm(a, 1) * np.linalg.norm(np.linalg.inv(a), 1)))


def residual_reported_in_row_units(scenario: Scenario, smallest: float) -> None:
    """Run `scenario` on 21 outputs at tolerance 1e-3 and check that each reported residual is
    max |C| / L^power at the reported q (plain rows), to round-off; the largest over `smallest`, so
    that the comparison is not between zeros."""
    system = ConstraintSystem(scenario)
    grid = np.asarray(scenario.times(steps=20))
    result = completed_run(scenario, grid, tolerance=1e-3)
    expected = [
        np.max(np.abs(system.residual(result.q[k], t) / system.row_scales)) for k, t in enumerate(grid)
    ]
    assert np.max(expected) > smallest
    np.testing.assert_allclose(result.residual, expected, rtol=0, atol=1e-15)
