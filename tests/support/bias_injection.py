"""A pytest plugin that injects a relative bias into one engine's accelerations, to show that the
suite catches it (the injected-bias experiment of `scripts/bias_experiment.py`).

Loaded only on request: `pytest -p tests.support.bias_injection` with `MBXVAL_BIAS_ENGINE` set to an
engine name (`reference` biases the native solver itself: its kinematic analysis and its forward
dynamics, so its truths too) and `MBXVAL_BIAS` to the relative bias (default 0.01). Every
acceleration the engine returns is multiplied by 1 + bias; nothing else changes.
"""

from __future__ import annotations

import dataclasses
import functools
import os
from collections.abc import Callable
from typing import Any

import pytest

ENGINE_VARIABLE = "MBXVAL_BIAS_ENGINE"
BIAS_VARIABLE = "MBXVAL_BIAS"


def biased_trajectory(trajectory: Any, factor: float) -> Any:
    """The trajectory with its accelerations scaled by `factor` (None stays None)."""
    if trajectory is None or trajectory.acceleration is None:
        return trajectory
    return dataclasses.replace(trajectory, acceleration=trajectory.acceleration * factor)


def _wrap(function: Callable[..., Any], bias: Callable[[Any], Any]) -> Callable[..., Any]:
    @functools.wraps(function)
    def wrapped(*args: Any, **kwargs: Any) -> Any:
        return bias(function(*args, **kwargs))

    return wrapped


def _bias_native(factor: float) -> None:
    import reference_solver
    import reference_solver.analysis as analysis
    import reference_solver.dynamics as dynamics
    import reference_solver.dynamics.forward as forward

    def motion(result: Any) -> Any:
        return dataclasses.replace(result, qdd=result.qdd * factor)

    def dynamic(result: Any) -> Any:
        return dataclasses.replace(result, motion=motion(result.motion))

    analyse = _wrap(analysis.analyse, motion)
    reference_solver.analyse = analysis.analyse = analyse  # type: ignore[assignment]
    simulate = _wrap(forward.simulate, dynamic)
    dynamics.simulate = forward.simulate = simulate  # type: ignore[assignment]


def _bias_engine(name: str, factor: float) -> None:
    import adapters

    cls = type(adapters.load(name))
    cls.simulate = _wrap(cls.simulate, lambda t: biased_trajectory(t, factor))  # type: ignore[method-assign]


def pytest_configure(config: pytest.Config) -> None:
    engine = os.environ.get(ENGINE_VARIABLE)
    if not engine:
        raise pytest.UsageError(f"bias_injection: set {ENGINE_VARIABLE} to an engine name")
    bias = float(os.environ.get(BIAS_VARIABLE, "0.01"))
    factor = 1.0 + bias
    if engine == "reference":
        _bias_native(factor)
    else:
        _bias_engine(engine, factor)


def pytest_report_header(config: pytest.Config) -> str:
    return (
        f"bias injection: {os.environ.get(ENGINE_VARIABLE)}'s accelerations x "
        f"(1 + {os.environ.get(BIAS_VARIABLE, '0.01')})"
    )
