"""The compiled path: the compiled kernel over a whole grid, handing anything abnormal to the plain path.

A scenario is compiled once (cached per scenario) into its instruction table. The kernel also
verifies the mobility: C_q square and clearly regular at the initial guess (then the plain
check_mobility passes too: a row subset of a regular matrix has full rank). When it cannot, and at
any event of the kernel, `analyse` returns None and the caller runs the plain path from the start, so
every error and diagnostic is the plain path's own.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from reference_solver.compiled.cache_guard import drop_stale_cache
from reference_solver.compiled.chunks import banded_point_seconds, chunks
from reference_solver.compiled.constraint_rows import NotCompiled
from reference_solver.compiled.loop import EVENTS, OK
from reference_solver.compiled.loop import run as run_kernel
from reference_solver.compiled.program import Program, compile_program
from reference_solver.diagnostics import RANK_TOLERANCE
from reference_solver.layout import Layout
from reference_solver.limits import ASSEMBLY_ITERATIONS, BACKTRACK_HALVINGS, SINGULAR_RCOND
from reference_solver.solution import Analysis
from reference_solver.system import ConstraintSystem
from scenarios.kept import kept
from scenarios.scenario import Scenario

HANDOVER = 100.0 * SINGULAR_RCOND
"""Below this reciprocal condition number the plain path decides (its estimate may differ a little)."""
MOBILITY_MARGIN = 100.0 * RANK_TOLERANCE
"""Mobility counts as verified when C_q at the guess has sqrt(rcond_1 rcond_inf) above this: that
bounds sigma_min / sigma_max from below (||A||_2^2 <= ||A||_1 ||A||_inf), and the plain check's rank
test needs sigma_min / sigma_max > RANK_TOLERANCE; the factor 100 covers the estimates (which can
only overstate rcond, in practice by less than 10)."""


@dataclass(frozen=True)
class Compiled:
    layout: Layout
    guess: np.ndarray
    program: Program | None
    reason: str
    """Why the program is None (no kernel for a constraint)."""


@dataclass(frozen=True)
class FastRun:
    event: str
    index: int
    """The time index of the event, len(grid) when the run completed."""
    analysis: Analysis | None


@kept(maxsize=32)
def compiled(scenario: Scenario) -> Compiled:
    """The scenario's program, or the reason it has none (kept for the last few scenarios)."""
    system = ConstraintSystem(scenario)
    guess = system.layout.initial_guess(scenario)
    try:
        program = compile_program(system)
    except NotCompiled as error:
        return Compiled(system.layout, guess, None, str(error))
    return Compiled(system.layout, guess, program, "")


def run(scenario: Scenario, grid: np.ndarray, tolerance: float = 1e-12, max_iterations: int = 25) -> FastRun:
    """The kernel's run over `grid`: its event, where it stopped, and the analysis if it completed."""
    c = compiled(scenario)
    if c.program is None:
        return FastRun(c.reason, 0, None)
    grid = np.ascontiguousarray(grid, dtype=float)
    count, n = grid.size, c.program.n
    q, qd, qdd = np.empty((count, n)), np.empty((count, n)), np.empty((count, n))
    iterations, residual, rcond = np.zeros(count, np.int64), np.zeros(count), np.zeros(count)
    if count == 0:
        return FastRun("empty grid", 0, None)
    drop_stale_cache()  # before the kernel's first call, when numba reads its on-disk cache
    state = np.zeros(1)
    for start, stop in chunks(count, banded_point_seconds(n)):  # a signal's handler runs between two
        event, index = run_kernel(
            *c.program, grid, c.guess, float(tolerance), int(max_iterations), ASSEMBLY_ITERATIONS,
            BACKTRACK_HALVINGS, HANDOVER, MOBILITY_MARGIN, q, qd, qdd, iterations, residual, rcond,
            start, stop, state,
        )  # fmt: skip
        if event != OK:
            return FastRun(EVENTS[event], int(index), None)
    return FastRun(EVENTS[OK], count, Analysis(c.layout, grid, q, qd, qdd, iterations, residual, rcond))


def analyse(scenario: Scenario, grid: np.ndarray, tolerance: float, max_iterations: int) -> Analysis | None:
    """The analysis on the compiled path, or None when the plain path must do it."""
    return run(scenario, grid, tolerance, max_iterations).analysis
