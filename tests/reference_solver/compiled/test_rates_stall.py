"""compiled.rates' stall rule (Newton on the dependent coordinates stops where round-off floors its
residual between RESIDUAL and STALLED), on the scene of test_partition_stall.py: the released
four-bar moved 10 m along x, whose pins' coordinates (about 10 m) have a spacing of floats of
3.6e-14 of L = 0.05 m, above RESIDUAL (1e-14), below STALLED (1e-12).

The kernel is called directly (not through CompiledPartitioned, whose retry would run the same
rule a second time), with C_D factored at every iteration (no chord) and the anchor's predictor
off, from the start's configuration with the crank turned: Newton proper, as the plain path's
Partitioned.positions, which test_partition_stall.py holds."""

from __future__ import annotations

import numpy as np

from reference_solver.dynamics.partition import RESIDUAL, STALLED
from tests.support.compiled_dynamics import compiled_and_plain
from tests.support.partitioned_scenes import SHIFT, four_bar

ANGLES = 30


def test_the_kernel_s_newton_stops_where_round_off_floors_the_residual() -> None:
    compiled, plain, start = compiled_and_plain(four_bar(SHIFT))
    _, near_plain, _ = compiled_and_plain(four_bar(0.0))
    assert plain.independent.tolist() == near_plain.independent.tolist() == [2]  # the crank's angle
    k = compiled.kernels
    sizes = compiled.index[k.SIZES]
    floored = 0
    for step in range(ANGLES):
        crank = np.array([start.q[2] + 0.01 * step])
        compiled.restart(start.q)
        sizes[k.S_CHORD], sizes[k.S_HAS_FACTORS] = 0, 0
        status, residual = k.partitioned(
            k.POSITIONS, 0.0, crank.copy(), compiled.nothing, *compiled.arguments
        )
        # without the rule (STALLED = 0, tried): NOT_CONVERGED at all 30 angles, after 12 iterations
        assert status == k.OK, step
        q = compiled.vec[k.Q, : start.q.size].copy()
        miss = np.max(np.abs(plain.system.residual(q, 0.0) / plain.system.row_scales))
        assert residual < STALLED and miss < STALLED
        floored += residual > RESIDUAL
        # the linkage at the origin, moved: the same positions to round-off of 10 m (1.8e-15)
        near_q, _ = near_plain.positions(0.0, crank)
        np.testing.assert_allclose(q, near_q + np.tile([SHIFT, 0.0, 0.0], 3), rtol=0, atol=5e-14)
    assert floored >= 20  # measured 30 (residuals 1.2e-14 to 3.1e-14)
