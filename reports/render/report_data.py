"""What a report reads: the stored rows, sidecar and trajectories of one results directory, and the
views the HTML and Markdown reports share (ordering, the status matrix, number formats)."""

from __future__ import annotations

import json
import math
import os
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field, replace
from typing import Any

import pandas as pd

import reports.render.plots as plots
from reports.render.clock import OLD_WALL, clock_label
from reports.render.drawings import read_drawings
from reports.store import TRUTH, Key, read_results, read_trajectories
from scenarios.trajectory import Trajectory

TABLE_COLUMNS = (
    "engine",
    "setting",
    "status",
    "error_position",
    "error_velocity",
    "error_acceleration",
    "position_length_max",
    "position_angle_max",
    "velocity_length_max",
    "velocity_angle_max",
    "acceleration_length_max",
    "acceleration_angle_max",
    "constraint_residual",
    "energy_drift",
    "driver_force_error",
    "reaction_error",
    "startup_excess",
    "startup_time",
    "build_time",
    "run_time",
    "steps",
    "message",
)
HEADINGS = {
    "error_position": "error pos",
    "error_velocity": "error vel",
    "error_acceleration": "error acc",
    "position_length_max": "pos max [m]",
    "position_angle_max": "pos max [rad]",
    "velocity_length_max": "vel max [m/s]",
    "velocity_angle_max": "vel max [rad/s]",
    "acceleration_length_max": "acc max [m/s²]",
    "acceleration_angle_max": "acc max [rad/s²]",
    "constraint_residual": "residual",
    "energy_drift": "energy drift",
    "driver_force_error": "driver force err",
    "reaction_error": "reaction err",
    "startup_excess": "start-up excess",
    "startup_time": "start-up [s]",
    "build_time": "build [s]",
    "run_time": "run [s]",
}


@dataclass(frozen=True)
class ReportData:
    frame: pd.DataFrame
    meta: dict[str, Any]
    trajectories: dict[Key, Trajectory]
    drawings: dict[str, str] = field(default_factory=dict)
    """{scenario: SVG} of the mechanisms the run drew beside its results (reports.render.drawings)."""

    def __post_init__(self) -> None:
        plots.use_stored_colours(self.meta.get("engine_colours"))  # the figures draw these

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> ReportData:
        frame, meta = read_results(path)
        try:
            trajectories = read_trajectories(path)
        except FileNotFoundError:  # lost: the report draws no curves until a resume rebuilds them
            trajectories = {}
        return cls(frame, readable_meta(meta), trajectories, read_drawings(path))

    def native_engine(self) -> str:
        """The native engine's name, as the run stored it ('' for a store from before it did)."""
        return str(self.meta.get("native_engine") or "")

    def scenarios(self) -> list[str]:
        """Scenarios in catalogue order (as the rows recorded it), unknown ones after them."""
        return _ordered(self.frame, "scenario", "scenario_rank")

    def engines(self) -> list[str]:
        """Engines in the registry's order (as the rows recorded it), the others after them in the
        order of the sidecar's engines (its run's), then by name."""
        return _ordered(self.frame, "engine", "engine_rank", [str(e) for e in self.meta.get("engines") or []])

    def rows(self, scenario: str) -> pd.DataFrame:
        return self.frame[self.frame["scenario"] == scenario]

    def default_row(self, scenario: str, engine: str) -> pd.Series | None:
        rows = self.frame[
            (self.frame["scenario"] == scenario) & (self.frame["engine"] == engine) & self.frame["is_default"]
        ]
        return None if rows.empty else rows.iloc[0]

    def truth(self, scenario: str) -> Trajectory | None:
        found = [t for (s, e, _), t in self.trajectories.items() if s == scenario and e == TRUTH]
        return found[0] if found else None

    def default_trajectories(self, scenario: str) -> dict[str, Trajectory]:
        """Each engine's default-setting trajectory of the scenario, by engine."""
        stored = {(s, e): t for (s, e, _), t in self.trajectories.items() if s == scenario and e != TRUTH}
        return {e: stored[(scenario, e)] for e in self.engines() if (scenario, e) in stored}

    def characteristic_length(self, scenario: str) -> float:
        return float(self.rows(scenario)["characteristic_length"].iloc[0])

    def matrix(self) -> pd.DataFrame:
        """scenario x engine: the default setting's status and headline error, as text."""
        cells = {
            engine: [cell_text(self.default_row(s, engine)) for s in self.scenarios()]
            for engine in self.engines()
        }
        return pd.DataFrame(cells, index=self.scenarios())

    def unswept(self) -> ReportData:
        """The results without the points of parameter sweeps (drawn as maps, not one by one)."""
        return replace(self, frame=self.frame[~is_swept(self.frame)])

    def without(self, scenarios: Iterable[str]) -> ReportData:
        """The results without the rows of `scenarios` (drawn elsewhere, such as map cells)."""
        return replace(self, frame=self.frame[~self.frame["scenario"].isin(set(scenarios))])

    def status_counts(self) -> dict[str, int]:
        return {str(k): int(v) for k, v in self.frame["status"].value_counts().items()}


SIDECAR_SHAPES: dict[str, type | tuple[type, ...]] = {
    "engines": Mapping,
    "packages": Mapping,
    "machine": Mapping,
    "engine_colours": Mapping,
    "revisions": list,
    "repeats": (int, float),
    "warmup": (int, float),
    "timeout": (int, float),
}
"""The shape of each sidecar field the report reads that is not text (text fields are shown as
text whatever they hold)."""


def readable_meta(meta: Mapping[str, Any]) -> dict[str, Any]:
    """The sidecar as the report reads it: a field of another shape than a run writes (a store
    edited by hand) is left out, so the page says '?' or nothing there instead of failing."""
    return {k: v for k, v in meta.items() if isinstance(v, SIDECAR_SHAPES.get(k, object))}


def is_swept(frame: pd.DataFrame) -> pd.Series:
    """Which rows are points of a parameter sweep (a `sweep` cell that holds their values)."""
    if "sweep" not in frame:
        return pd.Series(False, index=frame.index)
    return frame["sweep"].map(lambda cell: swept_point(cell) is not None).astype(bool)


def swept_point(cell: object) -> dict[str, str] | None:
    """The parameter values a row's `sweep` cell holds (the JSON object of names to values a run
    stores, reports.run.rows), or None: off a sweep, and for a cell that holds anything else (a
    store edited by hand), whose row is then drawn as an unswept one rather than failing the map."""
    if not isinstance(cell, str) or not cell:
        return None
    try:
        values = json.loads(cell)
    except (ValueError, RecursionError):
        return None
    if not isinstance(values, dict) or not values:
        return None
    if not all(isinstance(v, str | int | float) and not isinstance(v, bool) for v in values.values()):
        return None
    return {str(k): str(v) for k, v in values.items()}


def map_cell_rows(frame: pd.DataFrame) -> pd.DataFrame:
    """The rows at a cell of the dynamics' stiffness-step map (their cell recorded with them)."""
    if "map_stiffness" not in frame:
        return frame.iloc[0:0]
    return frame[frame["map_stiffness"].notna()]


def revision_label(meta: dict[str, Any]) -> str:
    """The git revision of stored results as a report states it: the run's revision, and every
    other revision its rows were made under (rows kept with --keep-stale), so a resume after a new
    commit never passes old rows off as new ones."""
    revision = str(meta.get("git_revision", "?"))[:12]
    others = [str(r)[:12] for r in meta.get("revisions", []) if str(r)[:12] != revision]
    return f"{revision} (some rows from {', '.join(others)}, marked stale)" if others else revision


def timing_note(rows: pd.DataFrame) -> str:
    """Where the run times were measured and alongside how many other runs (parallel workers
    share the machine, so their wall times are longer than one-by-one runs'), and on which clock."""
    return f"{_where_timed(rows)} {clock_note(rows)}"


def _where_timed(rows: pd.DataFrame) -> str:
    if "workers" not in rows or rows.empty:
        return "Run times: where and how many at once not recorded (results from before that)."
    hosts = sorted({str(h) for h in rows["host"] if str(h)}) or ["an unrecorded host"]
    counts = sorted({int(w) for w in rows["workers"] if int(w) > 0})
    if not counts:
        return f"Run times measured on {', '.join(hosts)}; how many runs at once was not recorded."
    ways = " and ".join("one at a time" if w == 1 else f"{w} at once (Dask workers)" for w in counts)
    note = f"Run times measured on {', '.join(hosts)}, {ways}"
    if counts != [1]:
        note += "; runs made in parallel share the machine, so their wall times are longer than serial ones"
    return note + "."


def clock_note(rows: pd.DataFrame) -> str:
    """Which clock the rows' run times were read on (reports.render.clock), as a sentence."""
    shown = clock_label(rows)
    return f"Run times are {shown} seconds{'' if shown == OLD_WALL else f' ({CLOCKS})'}."


CLOCKS = (
    "CPU: the process CPU time of the run's worker, every thread of it, one BLAS thread per worker; "
    "the wall clock's figure is stored beside it, as run_time_wall"
)


DRIFT_MARK = " ⚠"
"""Beside an ok run's errors, wherever they are shown, when its own figures say it drifted (the
stored `self_check` column, scoring.self_check; no truth used)."""
ERROR_COLUMNS = ("error_position", "error_velocity", "error_acceleration")


def drift_mark(row: pd.Series | dict[str, Any]) -> str:
    """DRIFT_MARK for an ok row its run called drifted, else ''."""
    drift = row.get("self_check")
    drifted = isinstance(drift, str) and drift != ""
    return DRIFT_MARK if drifted and row.get("status") == "ok" else ""


def cell_text(row: pd.Series | None) -> str:
    if row is None:
        return "not run"
    if row["status"] != "ok":
        return str(row["status"])
    levels = [row.get(c, math.nan) for c in ERROR_COLUMNS]
    if all(isinstance(v, float) and math.isnan(v) for v in levels):  # results from before the levels
        return f"ok {number(row['error'])}{drift_mark(row)}"
    return "ok " + " / ".join(number(v) for v in levels) + drift_mark(row)


def number(value: Any) -> str:
    """Compact scientific text; an en dash for a value left out."""
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "–"
    if isinstance(value, int | float) and not isinstance(value, bool):
        return "0" if value == 0 else f"{value:.2e}"
    return str(value)


def table(rows: pd.DataFrame) -> pd.DataFrame:
    """The per-scenario table: TABLE_COLUMNS, numbers as compact text (the errors of a drifted row
    marked), sorted by engine, mode and setting (numerically: setting_key)."""
    for column in TABLE_COLUMNS:  # results written before a column existed
        if column not in rows:
            rows = rows.assign(**{column: math.nan})
    order = sorted(
        range(len(rows)),
        key=lambda k: (
            str(rows["engine"].iloc[k]),
            str(rows["mode"].iloc[k]),
            setting_key(rows["setting"].iloc[k]),
        ),
    )
    ordered = rows.iloc[order]
    marks = [drift_mark(row) for _, row in ordered.iterrows()]
    shown = ordered[list(TABLE_COLUMNS)].copy()
    for column in TABLE_COLUMNS:
        if column not in ("engine", "setting", "status", "message", "steps"):
            shown[column] = [number(v) for v in shown[column]]
    for column in ERROR_COLUMNS:
        shown[column] = [text + mark for text, mark in zip(shown[column], marks, strict=True)]
    shown["message"] = [str(m)[:160] for m in shown["message"]]
    return shown.reset_index(drop=True).rename(columns=HEADINGS)


def _ordered(frame: pd.DataFrame, column: str, rank: str, stored: Iterable[str] = ()) -> list[str]:
    """The distinct values of `column`: those with a recorded `rank` by it; then the others (a name
    not listed when its row was made, or a row stored before the ranks were recorded) in the
    `stored` order, then in the order they were first run (`recorded_at`), then by name."""
    ranks: dict[str, int] = {}
    first: dict[str, str] = {}
    recorded = frame[rank].fillna(-1).astype(int) if rank in frame else pd.Series(-1, frame.index)
    times = (
        frame["recorded_at"].fillna("").astype(str) if "recorded_at" in frame else pd.Series("", frame.index)
    )
    for value, place, when in zip(frame[column].astype(str), recorded, times, strict=True):
        ranks[value] = max(ranks.get(value, -1), int(place))
        first[value] = min(first.get(value, when), when)
    order = list(stored)
    listed = sorted((r, v) for v, r in ranks.items() if r >= 0)
    others = sorted(
        (v for v, r in ranks.items() if r < 0),
        key=lambda v: (order.index(v) if v in order else len(order), first[v], v),
    )
    return [v for _, v in listed] + others


def setting_key(setting: object) -> tuple[tuple[str, int, float, str], ...]:
    """A setting label's sort key: its words in order, each `key=value` by the value's number where
    it is one (1e-08 before 1e-06 before 0.0001), by its text otherwise (after the numbers)."""
    words: list[tuple[str, int, float, str]] = []
    for word in str(setting).split(" "):
        key, _, value = word.partition("=")
        try:
            words.append((key, 0, float(value), ""))
        except ValueError:
            words.append((key, 1, 0.0, value))
    return tuple(words)
