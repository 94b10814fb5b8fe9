"""The compiled fast path of the reference solver (numba), beside the plain path it must agree with.

`analyse` returns the Analysis, or None when the plain path must run: numba is not installed, the
scenario has a constraint with no kernel, or the kernel met anything abnormal (see fast.path).
"""

from __future__ import annotations

from importlib.util import find_spec
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from reference_solver.solution import Analysis
    from scenarios.scenario import Scenario

AVAILABLE = find_spec("numba") is not None


def analyse(scenario: Scenario, grid: np.ndarray, tolerance: float, max_iterations: int) -> Analysis | None:
    if not AVAILABLE:
        return None
    from reference_solver.fast import path

    return path.analyse(scenario, grid, tolerance, max_iterations)
