"""What each engine mode measures, declared as data beside the mode.

A row's error is a claim about an engine only when the row says whose computation produced it: the
engine's own integrator, or a Newton loop written in the adapter on the engine's kinematics; and
which levels were derived by the adapter (a linear solve on the engine's Jacobian, finite
differences) rather than read from the engine's state.
"""

from __future__ import annotations

from dataclasses import dataclass

ENGINE = "engine"
"""`Mode.kind` of a mode run by the engine's own solver or integrator."""
ADAPTER = "adapter"
"""`Mode.kind` of a mode run by a loop in the adapter on the engine's kinematics."""


@dataclass(frozen=True)
class Mode:
    """One mode of an engine: its name (Setting.mode), who computes the positions (`kind`), what it
    runs in one phrase, and the levels the adapter derives with how ({level: how})."""

    name: str
    kind: str
    runs: str
    derived: tuple[tuple[str, str], ...] = ()

    @property
    def measures(self) -> str:
        """One line for `mbxval list` and the `measures` column."""
        who = "engine's own solver" if self.kind == ENGINE else "adapter loop on the engine's kinematics"
        text = f"{who}: {self.runs}"
        if self.derived:
            text += "; derived: " + ", ".join(f"{level} ({how})" for level, how in self.derived)
        return text


def measures_of(modes: tuple[Mode, ...], mode: str) -> str:
    """The `measures` text of `mode` among `modes` ('' for a mode not declared)."""
    return next((m.measures for m in modes if m.name == mode), "")
