"""The canonical trajectory: what every engine returns and every comparison reads.

For each output body, on the scenario's time grid: the global position (x, y) of its body frame's
origin and its angle theta (continuous, never wrapped), with their first and second time
derivatives. A level an engine cannot give is None, never filled in.
"""

from __future__ import annotations

import csv
from dataclasses import dataclass, field
from typing import IO, TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:  # pandas is imported where a frame is asked for: a solve writes its CSV without it
    import pandas as pd

from scenarios.scenario import Level

COLUMNS: dict[Level, tuple[str, str, str]] = {
    "position": ("x", "y", "theta"),
    "velocity": ("vx", "vy", "omega"),
    "acceleration": ("ax", "ay", "alpha"),
}
CSV_BLOCK_ROWS = 4096
"""Rows `write_csv` turns into Python numbers at once: one call for a million rows holds the
interpreter (and a Ctrl-C's or SIGTERM's handler) for a second and the memory of every row."""


@dataclass(frozen=True)
class Trajectory:
    """Arrays of shape (len(times), len(bodies), 3) per level; `extras` are named (len(times),)
    arrays such as a cam's contact parameter."""

    times: np.ndarray
    bodies: tuple[str, ...]
    position: np.ndarray | None = None
    velocity: np.ndarray | None = None
    acceleration: np.ndarray | None = None
    extras: dict[str, np.ndarray] = field(default_factory=dict)

    def __post_init__(self) -> None:
        shape = (len(self.times), len(self.bodies), 3)
        for level in COLUMNS:
            values = getattr(self, level)
            if values is not None and np.shape(values) != shape:
                raise ValueError(f"{level} has shape {np.shape(values)}, expected {shape}")

    @property
    def levels(self) -> tuple[Level, ...]:
        """The levels this trajectory really has."""
        return tuple(level for level in COLUMNS if getattr(self, level) is not None)

    def level(self, level: Level) -> np.ndarray | None:
        return getattr(self, level)  # type: ignore[no-any-return]

    def select(self, bodies: tuple[str, ...]) -> Trajectory:
        """The same trajectory restricted to `bodies`, in that order."""
        index = [self.bodies.index(b) for b in bodies]
        pick = {lv: (None if (a := self.level(lv)) is None else a[:, index, :]) for lv in COLUMNS}
        return Trajectory(self.times, bodies, extras=dict(self.extras), **pick)

    def is_finite(self) -> bool:
        arrays = [self.level(lv) for lv in self.levels] + list(self.extras.values())
        return all(np.all(np.isfinite(a)) for a in arrays if a is not None)

    def to_frame(self) -> pd.DataFrame:
        """Column t, then <body>.x <body>.y <body>.theta <body>.vx ... per body, then extras."""
        import pandas as pd

        return pd.DataFrame(self.columns())

    def columns(self) -> dict[str, np.ndarray]:
        """The columns of `to_frame` by name, as arrays (without building a frame)."""
        data: dict[str, np.ndarray] = {"t": np.asarray(self.times, dtype=float)}
        for k, body in enumerate(self.bodies):
            for level, names in COLUMNS.items():
                values = self.level(level)
                if values is not None:
                    for c, name in enumerate(names):
                        data[f"{body}.{name}"] = values[:, k, c]
        data.update(self.extras)
        return data

    @classmethod
    def from_frame(cls, frame: pd.DataFrame) -> Trajectory:
        """Read back what `to_frame` wrote."""
        bodies = tuple(dict.fromkeys(c.rsplit(".", 1)[0] for c in frame.columns if c.endswith(".x")))
        arrays: dict[str, np.ndarray | None] = {}
        for level, names in COLUMNS.items():
            cols = [[f"{b}.{n}" for n in names] for b in bodies]
            present = all(c in frame.columns for row in cols for c in row)
            arrays[level] = (
                np.stack([frame[row].to_numpy(dtype=float) for row in cols], axis=1)
                if present and bodies
                else None
            )
        known = {"t"} | {f"{b}.{n}" for b in bodies for names in COLUMNS.values() for n in names}
        extras = {c: frame[c].to_numpy(dtype=float) for c in frame.columns if c not in known}
        return cls(frame["t"].to_numpy(dtype=float), bodies, extras=extras, **arrays)

    def write_csv(self, stream: IO[str]) -> None:
        """The columns of `to_frame` as CSV, every number to 17 significant digits (round-trips),
        a NaN as an empty field: as pandas writes the frame, without importing pandas."""
        columns = self.columns()
        writer = csv.writer(stream, lineterminator="\n")
        writer.writerow(columns)
        values = np.column_stack([np.asarray(v, dtype=float) for v in columns.values()])
        for start in range(0, len(values), CSV_BLOCK_ROWS):
            for row in values[start : start + CSV_BLOCK_ROWS].tolist():
                writer.writerow(["" if x != x else f"{x:.17g}" for x in row])
