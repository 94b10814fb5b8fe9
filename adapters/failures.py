"""How an engine run can end without a trajectory (the statuses and the exceptions an adapter raises),
and the error for a setting an engine does not have."""

from __future__ import annotations

from typing import ClassVar, Literal

Status = Literal["ok", "failed", "diverged", "singular", "timeout", "unsupported"]
STATUSES: tuple[Status, ...] = ("ok", "failed", "diverged", "singular", "timeout", "unsupported")


class EngineFailure(Exception):
    """An engine run that ended without a trajectory. `time` is the simulated time it happened."""

    status: ClassVar[Status] = "failed"

    def __init__(self, message: str, time: float | None = None) -> None:
        super().__init__(message)
        self.time = time


class Diverged(EngineFailure):
    """The simulation became unstable (exploding or non-finite state)."""

    status: ClassVar[Status] = "diverged"


class Singular(EngineFailure):
    """The constraint Jacobian became singular, or the solver met a singular configuration."""

    status: ClassVar[Status] = "singular"


class Unsupported(EngineFailure):
    """The engine cannot represent this scenario faithfully."""

    status: ClassVar[Status] = "unsupported"


class SettingError(ValueError):
    """A setting the engine does not have: an unknown mode or option, or a value out of its range."""
