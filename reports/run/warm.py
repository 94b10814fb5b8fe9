"""Making a process ready for the runs it forks: the native solver's compiled kernels loaded and each
scenario's instruction table built before any run's clock starts.

A forked run inherits what its parent holds, and loses what it loads itself. The native solver loads
its compiled kernels (numba's on-disk cache) at its first call, about 0.65 s, and builds a scenario's
program at its first solve of that scenario: a child forked from a cold parent paid both on every
run. Warmed here once per process and once per scenario, every forked worker starts with them (a
worker kept for later groups builds a later scenario's program in its own untimed warm-up run).

The warm-up is our own solver on the scenario's first two grid times and the constraint residual
on them (every run's comparison measures it, with reference_solver.compiled.residuals), run like
the truth (in the runner's process with a time limit when that is the main thread; a Dask worker's
task thread, where no alarm can be set, calls it directly: two grid times, a bounded Newton loop).
Its failure is ignored: a run that cannot be made then fails on its own, with its own message.
"""

from __future__ import annotations

import contextlib
import threading
from collections import Counter

import numpy as np

from reports.run.isolation import run_here
from scenarios import Scenario
from scenarios import load as build_scenario

KERNEL_SCENARIO = "four_bar"
"""A small built-in kinematic scenario whose solve loads the kernels (a Dask worker's setup)."""
WARM_TIMEOUT = 60.0
counts: Counter[str] = Counter()
"""What this process warmed: 'kernels' (loaded once) and 'scenarios' (one per distinct scenario)."""
_warmed: set[Scenario] = set()


def warm(scenario: Scenario, timeout: float = WARM_TIMEOUT) -> None:
    """Solve `scenario` natively on its first two grid times in this process, once per scenario, so
    that the kernels and the scenario's program are here before a run is forked. Dynamic scenarios
    are left out: their truth is solved natively in this process already."""
    if scenario.analysis == "dynamic":
        return
    try:
        if scenario in _warmed:
            return
        _warmed.add(scenario)
    except TypeError:  # an unhashable scenario is not kept by the solver's program cache either
        return
    counts["scenarios"] += 1
    _solve_start(scenario, timeout)


def warm_kernels() -> None:
    """Load the native kernels in this process (a Dask worker's setup), on a built-in scenario;
    once per process, however often it is asked."""
    if counts["kernels"]:
        return
    counts["kernels"] += 1
    warm(build_scenario(KERNEL_SCENARIO))


def _solve_start(scenario: Scenario, timeout: float) -> None:
    from reference_solver import analyse, constraint_residual

    times = np.asarray(scenario.times(), dtype=float)[:2]

    def start() -> None:  # the residual too: every run's comparison measures it with the kernels
        constraint_residual(scenario, analyse(scenario, times).trajectory())

    if threading.current_thread() is threading.main_thread():
        run_here(start, timeout)
        return
    with contextlib.suppress(Exception):  # the run meets the same problem and reports it
        start()
