"""The compiled path of the reference solver (numba), beside the plain path it must agree with.

`analyse` returns the Analysis, or None when the plain path must run: numba is not installed, the
scenario has a constraint with no kernel, or the kernel met anything abnormal (see compiled.path).
Where numba can cache its machine code nowhere (a read-only checkout with a read-only HOME and no
NUMBA_CACHE_DIR), its kernels cannot even be defined; the plain path then runs, and every solve
says so in a RuntimeWarning, which the run's warnings record.
"""

from __future__ import annotations

import warnings
from functools import lru_cache
from importlib import import_module
from importlib.util import find_spec
from types import ModuleType
from typing import TYPE_CHECKING

import numpy as np

from reference_solver.compiled.cache_guard import drop_stale_cache

if TYPE_CHECKING:
    from reference_solver.solution import Analysis
    from scenarios.scenario import Scenario

AVAILABLE = find_spec("numba") is not None
PAYS_FROM = 5_000
"""Constraint rows x grid points from which a compiled path pays for loading its kernels, where
they are not loaded yet: numba's import and a kernel family's load from its cache cost about 0.6 s
of CPU, what the plain path spends on some 5,000 row-steps (100 to 150 microseconds each)."""
_loaded: set[str] = set()
"""The kernel families (`_kernels` names, "path" for the kinematic loop) loaded in this process."""
_by_work = False
"""Whether `pays` weighs the work (`compile_where_it_pays`) or takes the compiled path always."""


def compile_where_it_pays() -> None:
    """Declare this process one command's (`mbxval solve`): from now on a compiled path left to
    `pays` is taken only where its kernels are loaded already or the work is at least PAYS_FROM
    row-steps, the plain path otherwise (the same results, tests/reference_solver/
    test_compiled_pays.py). A harness that times runs never declares it: its runs all take the
    compiled path, warmed before they are timed (reports.run.warm)."""
    global _by_work
    _by_work = True


def pays(family: str, rows: int, points: int, compiled: bool | None) -> bool:
    """Whether to take the compiled path of kernel `family` for `rows` constraint rows over
    `points` grid times: `compiled` True or False decides; None is True unless the process weighs
    the work (compile_where_it_pays), where it is True for loaded kernels or enough work."""
    if compiled is not None:
        return compiled
    return not _by_work or family in _loaded or rows * points >= PAYS_FROM


def analyse(scenario: Scenario, grid: np.ndarray, tolerance: float, max_iterations: int) -> Analysis | None:
    if not AVAILABLE:
        return None
    path, problem = _compiled()
    if path is None:
        warnings.warn(f"native solver: the plain path runs, {problem}", RuntimeWarning, stacklevel=2)
        return None
    _loaded.add("path")
    result: Analysis | None = path.analyse(scenario, grid, tolerance, max_iterations)
    return result


@lru_cache(maxsize=1)
def _compiled() -> tuple[ModuleType | None, str]:
    """The compiled path's module, or None and why it cannot be defined here."""
    try:
        from reference_solver.compiled import path
    except RuntimeError as error:  # numba: "cannot cache function ...: no locator available"
        if "cannot cache" not in str(error):
            raise
        return None, f"numba cannot cache its compiled kernels anywhere writable ({error})"
    return path, ""


def dense_kernels() -> tuple[ModuleType | None, str]:
    """The dense kernels' module (forward dynamics), or None and why it cannot be used here."""
    return _kernels("dense")


def rates_kernels() -> tuple[ModuleType | None, str]:
    """The partitioned right-hand side's module (forward dynamics, compiled.rates), or None and why."""
    return _kernels("rates")


def residual_kernels() -> tuple[ModuleType | None, str]:
    """The trajectory residual's module (reference_solver.residual, compiled.residuals), or None and why."""
    return _kernels("residuals")


def ali3p_kernels() -> tuple[ModuleType | None, str]:
    """ALI3-P's time-step module (forward dynamics, compiled.ali3p_kernel), or None and why."""
    return _kernels("ali3p_kernel")


def inverse_kernels() -> tuple[ModuleType | None, str]:
    """Inverse dynamics' module (dynamics.inverse, compiled.inverse_kernel), or None and why."""
    return _kernels("inverse_kernel")


@lru_cache(maxsize=8)
def _kernels(name: str) -> tuple[ModuleType | None, str]:
    if not AVAILABLE:
        return None, "numba is not installed"
    drop_stale_cache()
    try:
        module = import_module(f"reference_solver.compiled.{name}")
    except RuntimeError as error:  # as in _compiled
        if "cannot cache" not in str(error):
            raise
        return None, f"numba cannot cache its compiled kernels anywhere writable ({error})"
    _loaded.add(name)
    return module, ""
