"""The stability map of a parameter sweep, as data: for every swept point and engine, the verdict of
the engine's default setting as its row stored it when the run was made (reports.stress.recording:
ok, wrong branch, drifted, diverged, singular detected, ...; "not recorded" in a store from before),
its error and when it happened, on the grid of the swept values.

The rows of one sweep share a base scenario and the swept parameters (the `sweep` column); the axes
are those parameters in the order they were swept, each value sorted (numerically where it is a
number). The native solver's singular points are the points where it detected a singular
configuration: the map marks them on every engine's panel.
"""

from __future__ import annotations

from dataclasses import dataclass

import pandas as pd

from reports.render.report_data import ReportData, is_swept, swept_point
from reports.render.stored_verdicts import judgement

SINGULAR = "singular detected"
Value = float | str


@dataclass(frozen=True)
class Cell:
    """One engine at one swept point: where it sits on the grid and what became of its run."""

    point: str
    engine: str
    index: tuple[int, ...]  # the position of each axis's value
    verdict: str
    time: float
    error: float
    detail: str


@dataclass(frozen=True)
class SweptMap:
    """Every cell of one sweep: `base` scenario over `axes`, each with its sorted `values`."""

    base: str
    axes: tuple[str, ...]
    values: tuple[tuple[Value, ...], ...]
    engines: tuple[str, ...]
    cells: tuple[Cell, ...]
    native: str = ""
    """The native engine's name as the store records it ('' where it does not)."""

    def native_singular(self) -> set[tuple[int, ...]]:
        """Grid positions where the native solver detected a singular configuration."""
        return {c.index for c in self.cells if c.engine == self.native and c.verdict == SINGULAR}

    def cell(self, engine: str, **values: Value) -> Cell:
        """The cell of `engine` at the given values of every axis (KeyError if there is none)."""
        index = tuple(self.values[k].index(_value(str(values[a]))) for k, a in enumerate(self.axes))
        for found in self.cells:
            if found.engine == engine and found.index == index:
                return found
        raise KeyError((engine, values))


def swept_maps(data: ReportData) -> list[SweptMap]:
    """One map per base scenario and set of swept parameters, from the default-setting rows."""
    frame = data.frame[is_swept(data.frame) & data.frame["is_default"].astype(bool)]
    groups: dict[tuple[str, tuple[str, ...]], list[pd.Series]] = {}
    for _, row in frame.iterrows():
        swept = swept_point(row["sweep"]) or {}  # is_swept kept only the rows whose cell reads
        groups.setdefault((base_name(str(row["scenario"])), tuple(swept)), []).append(row)
    return [_swept_map(data, base, axes, rows) for (base, axes), rows in groups.items()]


def _value(text: str) -> Value:
    try:
        return float(text)
    except ValueError:
        return text


def base_name(point: str) -> str:
    """The scenario a swept point's name (`base[NAME=VALUE,...]`) was made from."""
    return point[:-1].partition("[")[0] if point.endswith("]") and "[" in point else point


def _sorted(values: set[Value]) -> tuple[Value, ...]:
    numbers = sorted(v for v in values if isinstance(v, float))
    return (*numbers, *sorted(str(v) for v in values if not isinstance(v, float)))


def _swept_map(data: ReportData, base: str, axes: tuple[str, ...], rows: list[pd.Series]) -> SweptMap:
    points = {
        str(r["scenario"]): {k: _value(v) for k, v in (swept_point(r["sweep"]) or {}).items()} for r in rows
    }
    values = tuple(_sorted({p[a] for p in points.values()}) for a in axes)
    engines = [e for e in data.engines() if any(str(r["engine"]) == e for r in rows)]
    cells = []
    for row in rows:
        point = str(row["scenario"])
        index = tuple(values[k].index(points[point][a]) for k, a in enumerate(axes))
        judged = judgement(row)
        cells.append(
            Cell(point, judged.engine, index, judged.verdict, judged.time, judged.error, judged.detail)
        )
    return SweptMap(base, axes, values, tuple(engines), tuple(cells), data.native_engine())
