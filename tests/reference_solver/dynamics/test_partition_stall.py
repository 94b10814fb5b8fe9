"""Newton on the dependent coordinates (Partitioned.positions) where round-off floors its residual
between RESIDUAL and STALLED: the stall rule must end it there.

The released four-bar (four_bar_gravity, L = 0.05 m) moved 10 m along x: its pins' coordinates are
about 10 m, whose spacing of floats (1.8e-15 m) is 3.6e-14 of L, above RESIDUAL (1e-14) and below
STALLED (1e-12). Newton's residual stops falling there (measured 3.6e-14 at every crank angle
below); without the stall rule it runs out of iterations at every one of them (measured)."""

from __future__ import annotations

import numpy as np

from reference_solver.dynamics.partition import RESIDUAL, STALLED
from tests.support.partitioned_scenes import SHIFT, counted, four_bar, ode_of


def test_newton_stops_where_round_off_floors_the_residual() -> None:
    far, far_system = ode_of(four_bar(SHIFT))
    near, _ = ode_of(four_bar(0.0))
    assert far.independent.tolist() == near.independent.tolist() == [2]  # the crank's angle
    start = far.q.copy()
    floored = 0
    for k in range(30):
        crank = start[2] + 0.01 * k
        far.restart(start)
        calls = counted(far_system)
        q, _ = far.positions(0.0, np.array([crank]))
        del far_system.evaluate  # the class's own again
        residual = np.max(np.abs(far_system.residual(q, 0.0) / far_system.row_scales))
        assert residual < STALLED and len(calls) <= 8  # measured 2 to 7 (12 end in a ConvergenceError)
        floored += residual > RESIDUAL
        # the linkage at the origin, moved: the same positions to round-off of 10 m (1.8e-15)
        near.restart(near.q)
        q_near, _ = near.positions(0.0, np.array([crank]))
        moved = q_near + np.tile([SHIFT, 0.0, 0.0], 3)
        np.testing.assert_allclose(q, moved, rtol=0, atol=5e-14)  # measured 1.8e-14
    assert floored >= 20  # measured 30
