"""A run-in for Exudyn's index-3 generalized-alpha on kinematically driven scenes: the march starts
steps before the first output time, so that the method's start-up transient has died out by then.

Index-3 generalized-alpha (Arnold and Brüls 2007, the algorithm Exudyn implements) carries its
velocities with an O(h^2) error and its algorithmic accelerations a quarter-step ahead of the
motion; a start from the exact state (q, v, a) at t0 is therefore off the method's own smooth
solution by O(h^2) in velocity, which the position constraints turn into an O(h) error in the
accelerations and constraint forces. Its error recursion has a double root at -rho (the spectral
radius), so the transient grows and decays as n rho^n over the steps n. Exudyn's
initial-acceleration solve does not remove it (it gives the exact accelerations, which the start
already has), a smaller rho shortens it but costs accuracy at every later step, and the index-2
variants drift in position (docs/settings-rule.md measures each).

So a kinematic scene's march starts `run_in_steps(rho)` steps before the first output, from the
mechanism assembled there (Newton on Exudyn's own constraints, stepped back from the assembled
start, then the same rate solves as the start), and its first `n` steps are not output. Exudyn
refuses a negative start time by a range check only: it is switched off for the solve
(`negative_times`), the drivers' laws being defined for every time.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any

import exudyn as exu
import numpy as np

from adapters.base import EngineFailure
from adapters.exudyn.assembly import INITIAL, ConstraintProbe, States, coordinate_scales
from adapters.exudyn.model import ExudynModel

DECAY = 1e-9
"""The run-in lasts until the transient's envelope n rho^n has fallen below this."""
MAX_RUN_IN = 1000
"""Steps at most (rho near 1 decays too slowly for any run-in to pay)."""


def run_in_steps(rho: float) -> int:
    """The steps of run-in that generalized-alpha at spectral radius `rho` needs: the least n with
    n rho^n <= DECAY (the envelope of its double root), at most MAX_RUN_IN."""
    if rho <= 0.0:
        return 1
    if rho >= 1.0:
        return MAX_RUN_IN
    n = 1
    while n < MAX_RUN_IN and n * rho**n > DECAY:
        n += 1
    return n


@contextmanager
def negative_times() -> Iterator[None]:
    """Exudyn's parameter range checks off for the duration (they refuse a negative start time;
    a process-wide switch, restored after)."""
    checks = exu.special.exceptions
    before = checks.parameterRangeChecks
    checks.parameterRangeChecks = False
    try:
        yield
    finally:
        checks.parameterRangeChecks = before


Constraints = Callable[[np.ndarray, float], np.ndarray]


def positions_back(
    jacobian: Constraints, residual: Constraints, q0: np.ndarray, t0: float, h: float, n: int, size: float
) -> np.ndarray:
    """The assembled positions at t0 - n h, stepped back from `q0` (assembled at t0) one step at a
    time: a secant predictor and full Newton on the constraints `residual(q, t)` with their
    `jacobian(q, t)`, to round-off of `size`."""
    previous, q = q0.copy(), q0.copy()
    for k in range(1, n + 1):
        t = t0 - k * h
        q, previous = 2.0 * q - previous, q
        for _ in range(20):
            step = np.linalg.solve(jacobian(q, t), residual(q, t))
            q = q - step
            if float(np.max(np.abs(step))) <= 1e-15 * size:
                break
        else:
            raise EngineFailure(f"the run-in's assembly did not converge at t = {t:.6g}", t)
        if not math.isfinite(float(np.max(np.abs(q)))):
            raise EngineFailure(f"the run-in's assembly diverged at t = {t:.6g}", t)
    return q


def run_in_start(model: ExudynModel, settings: Any, t0: float, h: float, n: int) -> States | str:
    """The consistent state at t0 - n h: the mechanism assembled there (positions stepped back from
    the start at t0 on Exudyn's constraints), its rates solved as the start's; or why it cannot be
    (no configuration before the start: a dead point, a singular Jacobian). Kept per (t0, h, n)."""
    key = (t0, h, n)
    if key not in model.run_in_starts:
        start = np.array(model.mbs.systemData.GetODE2Coordinates(INITIAL))
        probe = ConstraintProbe(model, settings)
        size = max(1.0, float(np.max(np.abs(start))))
        try:
            with negative_times():
                q = positions_back(probe.jacobian, probe.residual, start, t0, h, n, size)
                v, a = probe.rates(q, t0 - n * h, *coordinate_scales(model))
            model.run_in_starts[key] = States(q[None, :], v[None, :], a[None, :])
        except (EngineFailure, np.linalg.LinAlgError) as error:
            model.run_in_starts[key] = str(error)
        finally:
            probe.close(settings)
    found: States | str = model.run_in_starts[key]
    return found


NO_RUN_IN = (
    "Exudyn: no run-in ({reason}): generalized-alpha starts at the first output, its start-up "
    "transient included"
)
