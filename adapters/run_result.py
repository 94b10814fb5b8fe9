"""What one engine run gives back (RunResult: always a status; a trajectory only when ok) and how
an engine's outcome becomes one: what it raised as a status, message and failure time, its Python
warnings as one-line texts, the first time a trajectory stops being finite. adapters.base.Adapter.run
builds every RunResult from these; plug-ins import RunResult from adapters.base."""

from __future__ import annotations

import math
import traceback
import warnings
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from adapters.failures import EngineFailure, Status
from adapters.setting import Setting
from scenarios.trajectory import Trajectory


@dataclass(frozen=True)
class RunResult:
    """The outcome of one engine run: always a status; a trajectory only when the status is ok."""

    engine: str
    version: str
    setting: Setting
    status: Status
    message: str = ""
    trajectory: Trajectory | None = None
    build_time: float = math.nan
    """CPU seconds to build the model (for a run that failed in the build, up to the failure)."""
    run_time: float = math.nan
    """CPU seconds to simulate: the minimum of the timed repeats (empty for a run that is not ok)."""
    warmup_time: float = math.nan
    """CPU seconds spent in the untimed warm-up runs, summed (0 without a warm-up); a run that
    failed, up to its failure (adapters.spent), as for the build and the repeats."""
    repeats_time: float = math.nan
    """CPU seconds spent in the timed repeats, summed (`run_time` is their minimum)."""
    build_time_wall: float = math.nan
    """`build_time` on the wall clock."""
    run_time_wall: float = math.nan
    """Wall seconds to simulate: the minimum of the same timed repeats."""
    warmup_time_wall: float = math.nan
    """`warmup_time` on the wall clock."""
    repeats_time_wall: float = math.nan
    """`repeats_time` on the wall clock."""
    repeats: int = 0
    """Timed repeats made (one where the first took longer than the run's `once_above`)."""
    steps: int = 0
    failure_time: float | None = None
    warnings: tuple[str, ...] = field(default=())
    measures: str = ""
    """What the setting's mode measures (adapters.modes)."""


def failure_fields(error: Exception) -> dict[str, Any]:
    """A run's status, message and failure time from what its engine raised: an EngineFailure says
    them itself; any other exception is `failed`, named with where it was raised."""
    if isinstance(error, EngineFailure):
        return {"status": error.status, "message": one_line(str(error)), "failure_time": error.time}
    where = traceback.extract_tb(error.__traceback__)[-1]
    message = f"{type(error).__name__}: {error} (at {where.name}:{where.lineno})"
    return {"status": "failed", "message": one_line(message)}


def one_line(text: str) -> str:
    """The text on one line, at most 500 characters (a row's message)."""
    return " ".join(text.split())[:500]


def warning_texts(caught: list[warnings.WarningMessage]) -> tuple[str, ...]:
    """The distinct warnings a run raised, each as one line naming its category."""
    return tuple(dict.fromkeys(one_line(f"{w.category.__name__}: {w.message}") for w in caught))


def first_nonfinite_time(trajectory: Trajectory) -> float | None:
    """The first grid time where any level or extra is not finite, or None."""
    bad = np.zeros(len(trajectory.times), dtype=bool)
    for level in trajectory.levels:
        values = trajectory.level(level)
        assert values is not None
        bad |= ~np.isfinite(values).all(axis=(1, 2))
    for values in trajectory.extras.values():
        bad |= ~np.isfinite(values)
    hits = np.flatnonzero(bad)
    return float(trajectory.times[hits[0]]) if hits.size else None
