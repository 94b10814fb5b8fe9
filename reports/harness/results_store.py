"""Stored results: tidy rows in results.parquet, a JSON sidecar results.json, and the trajectories
the report draws (each engine's default-setting run and the reference truth) in trajectories.parquet.

One row per run, keyed by (scenario, engine, setting). A save commits all three files together as
a new generation with their checksums (reports.harness.store_files); a load verifies them, and a
store that does not verify, or whose rows lack the columns every row has, is refused as damaged
(StoreDamaged), never read or copied forward. A lost trajectories file is not damage: its rows
stay, and `lost_trajectories` tells a resume to rebuild what the report draws.
"""

from __future__ import annotations

import json
import math
import os
from collections.abc import Iterable
from pathlib import Path
from typing import Any

import pandas as pd

from reports.harness import store_files
from reports.harness.columns import COLUMNS, DECLARED
from reports.harness.store_layout import damaged
from scenarios.trajectory import Trajectory

SCHEMA_VERSION = 1
RESULTS, SIDECAR, TRAJECTORIES = "results.parquet", "results.json", "trajectories.parquet"
KEY = ("scenario", "engine", "setting")
TRUTH = "truth"
REQUIRED = frozenset((*KEY, "engine_version", "mode", "options", "is_default", "status", "error"))
"""Columns every store has had; a declared column added since is filled with its empty value."""
Key = tuple[str, str, str]


def key_of(row: dict[str, Any]) -> Key:
    return (str(row["scenario"]), str(row["engine"]), str(row["setting"]))


class ResultsStore:
    """The rows and trajectories of one output directory, read at creation, written by `save`."""

    def __init__(self, directory: str | os.PathLike[str], fresh: bool = False) -> None:
        self.directory = Path(directory)
        self.rows: dict[Key, dict[str, Any]] = {}
        self.trajectories: dict[Key, Trajectory] = {}
        self.meta: dict[str, Any] = {}
        self.lost_trajectories = False
        if not fresh and store_files.committed(self.directory) is not None:
            frame, self.meta = read_results(self.directory)
            self.rows = {key_of(r): r for r in frame.to_dict("records")}
            try:
                self.trajectories = read_trajectories(self.directory)
            except FileNotFoundError:
                self.lost_trajectories = True

    def has(self, key: Key) -> bool:
        return key in self.rows

    def add(self, row: dict[str, Any], trajectory: Trajectory | None = None) -> None:
        missing = set(COLUMNS) - set(row)
        if missing:
            raise ValueError(f"row lacks columns {sorted(missing)}")
        self.rows[key_of(row)] = row
        if trajectory is not None:
            self.trajectories[key_of(row)] = trajectory

    def put_truth(self, scenario: str, label: str, trajectory: Trajectory) -> None:
        self.trajectories[(scenario, TRUTH, label)] = trajectory

    def frame(self) -> pd.DataFrame:
        return rows_frame(self.rows.values())

    def save(self, meta: dict[str, Any]) -> None:
        """Commit every file of the store at once (the sidecar gets `meta`, the schema version and
        the checksums). The caller holds the store's writer lock (reports.harness.store_lock)."""
        self.meta = {**meta, "schema_version": SCHEMA_VERSION}
        frame, trajectories = self.frame(), _trajectory_frame(self.trajectories)
        writers = {
            RESULTS: lambda path: frame.to_parquet(path, index=False),
            TRAJECTORIES: lambda path: trajectories.to_parquet(path, index=False),
        }
        store_files.commit(self.directory, writers, self.meta)
        self.lost_trajectories = False


def rows_frame(rows: Iterable[dict[str, Any]]) -> pd.DataFrame:
    """The tidy table, in COLUMNS order, plus one `opt_<name>` column per setting option."""
    frame = pd.DataFrame(list(rows), columns=list(COLUMNS))
    options = [json.loads(text) if isinstance(text, str) and text else {} for text in frame["options"]]
    for name in sorted({k for o in options for k in o}):
        values = [o.get(name) for o in options]
        numeric = all(v is None or (isinstance(v, int | float) and not isinstance(v, bool)) for v in values)
        frame[f"opt_{name}"] = [
            (math.nan if v is None else float(v)) if numeric else (None if v is None else str(v))
            for v in values
        ]
    return frame.sort_values(list(KEY), kind="stable").reset_index(drop=True)


def results_directory(path: str | os.PathLike[str]) -> Path:
    """The directory of stored results, given it or its results.parquet."""
    target = Path(path)
    if target.name == RESULTS and not target.is_dir():
        target = target.parent
    if store_files.committed(target) is None:
        raise FileNotFoundError(f"no {RESULTS} in {target}")
    return target


def _committed(path: str | os.PathLike[str]) -> tuple[Path, Path, dict[str, Any], set[str]]:
    """The store's directory, its committed generation, verified sidecar and absent files."""
    root = results_directory(path)
    generation = store_files.committed(root)
    assert generation is not None
    meta = store_files.read_sidecar(generation, root)
    absent = store_files.verify(generation, root, meta)
    if meta.get("schema_version", SCHEMA_VERSION) != SCHEMA_VERSION:
        raise damaged(root, f"schema version {meta['schema_version']}, this mbxval reads {SCHEMA_VERSION}")
    return root, generation, meta, absent


def read_results(path: str | os.PathLike[str]) -> tuple[pd.DataFrame, dict[str, Any]]:
    """The rows (without the derived opt_ columns) and the sidecar of stored results, verified:
    StoreDamaged for files that do not match their checksums or rows that lack required columns."""
    root, generation, meta, absent = _committed(path)
    if RESULTS in absent or not (generation / RESULTS).is_file():
        raise damaged(root, f"{RESULTS} is missing")
    try:
        frame = pd.read_parquet(generation / RESULTS)
    except Exception as error:  # pyarrow's errors have no common base worth naming
        raise damaged(root, f"{RESULTS} cannot be read: {type(error).__name__}") from error
    lacking = sorted(REQUIRED - set(frame.columns))
    if lacking:
        raise damaged(root, f"{RESULTS} lacks the columns {', '.join(lacking)}")
    if frame["status"].isna().any() or frame[list(KEY)].isna().any().any():
        raise damaged(root, f"{RESULTS} has rows without a status or key")
    for column in DECLARED:
        if column.name not in frame.columns:
            frame[column.name] = column.empty
    frame = frame[[c for c in COLUMNS if c in frame.columns]]
    return frame, meta


def read_trajectories(path: str | os.PathLike[str]) -> dict[Key, Trajectory]:
    """Every stored trajectory by (scenario, engine, setting); the truth under engine TRUTH.
    FileNotFoundError when the store has lost its trajectories file (a resume rebuilds it)."""
    root, generation, _, _ = _committed(path)
    file = generation / TRAJECTORIES
    if not file.is_file():
        raise FileNotFoundError(f"{root} has lost {TRAJECTORIES}")
    try:
        frame = pd.read_parquet(file)
    except Exception as error:
        raise damaged(root, f"{TRAJECTORIES} cannot be read: {type(error).__name__}") from error
    stored: dict[Key, Trajectory] = {}
    for key, part in frame.groupby(list(KEY), sort=False):
        columns = part.drop(columns=list(KEY)).dropna(axis=1, how="all").reset_index(drop=True)
        stored[(str(key[0]), str(key[1]), str(key[2]))] = Trajectory.from_frame(columns)
    return stored


def _trajectory_frame(trajectories: dict[Key, Trajectory]) -> pd.DataFrame:
    parts = []
    for (scenario, engine, setting), trajectory in trajectories.items():
        part = trajectory.to_frame()
        part.insert(0, "setting", setting)
        part.insert(0, "engine", engine)
        part.insert(0, "scenario", scenario)
        parts.append(part)
    return pd.concat(parts, ignore_index=True) if parts else pd.DataFrame(columns=list(KEY))
