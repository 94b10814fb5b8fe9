"""Stored results: tidy rows in results.parquet, a JSON sidecar results.json, and the trajectories
the report draws (each engine's default-setting run and the reference truth) in trajectories.parquet.

One row per run, keyed by (scenario, engine, setting). results.parquet and trajectories.parquet are
folders of Parquet parts (a pyarrow dataset each; reports.store.parts): a save writes what
changed since the last one as a new part and lists the older parts again, unread and unchanged, in
a new generation with every file's checksum (reports.store.files); so a save costs its batch.
A load reads the parts the sidecar lists, verified, and resolves them (the newest entry of a key
wins; reports.store.tables) into the same table a single file held before. A store that does
not verify, or whose rows lack the columns every row has, is refused as damaged (StoreDamaged), never
read or copied forward. A lost trajectories part is not damage: the rows stay, and
`lost_trajectories` tells a resume to rebuild what the report draws. A store an older mbxval wrote
(one results.parquet file, no parts) is read as it is and written whole, as parts, by its next save.
"""

from __future__ import annotations

import json
import math
import os
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

import reports.store.files as store_files
from reports.store.changes import ChangedRows, Changes
from reports.store.columns import COLUMNS, DECLARED
from reports.store.layout import CURRENT, damaged
from reports.store.layout import SCHEMA_VERSION as SCHEMA_VERSION  # its name here too
from reports.store.parts import plan_save
from reports.store.tables import (
    PART_COLUMN,
    PARTS,
    StoredTable,
    listed_parts,
    live_rows,
    members_of,
    part_frames,
    write_part,
)
from scenarios.trajectory import Trajectory

STORE_VERSION = 2
"""The sidecar's schema_version: 2 for tables as folders of parts (an mbxval from before parts
refuses it in one line, "schema version 2, this mbxval reads 1"), 1 for one file per table."""
READS = (1, STORE_VERSION)
RESULTS, SIDECAR, TRAJECTORIES = "results.parquet", "results.json", "trajectories.parquet"
KEY = ("scenario", "engine", "setting")
TRUTH = "truth"
REQUIRED = frozenset((*KEY, "engine_version", "mode", "options", "is_default", "status", "error"))
"""Columns every store has had; a declared column added since is filled with its empty value."""
CAP = {RESULTS: 5_000, TRAJECTORIES: 100}
"""Entries from which a part is sealed (merged no further; parts): rows, trajectories."""
Key = tuple[str, str, str]


def key_of(row: Mapping[str, Any]) -> Key:
    return (str(row["scenario"]), str(row["engine"]), str(row["setting"]))


class ResultsStore:
    """The rows and trajectories of one output directory, read at creation, written by `save`.
    `rows` and `trajectories` record what changes (reports.store.changes), so that a save
    writes only that; assigning either whole replaces the table."""

    def __init__(self, directory: str | os.PathLike[str], fresh: bool = False) -> None:
        self.directory = Path(directory)
        self._rows: ChangedRows[Key] = ChangedRows()
        self._trajectories: Changes[Key, Trajectory] = Changes()
        self.tables = {RESULTS: StoredTable(), TRAJECTORIES: StoredTable()}
        self.files: dict[str, dict[str, Any]] = {}  # the sidecar's files of the generation read
        self.meta: dict[str, Any] = {}
        self.lost_trajectories = False
        if not fresh and store_files.committed(self.directory) is not None:
            frame, self.meta, self.tables[RESULTS] = _read_rows(self.directory)
            self.files = dict(self.meta.get("files") or {})
            self._rows = ChangedRows({key_of(r): r for r in frame.to_dict("records")})
            try:
                trajectories, self.tables[TRAJECTORIES] = _read_trajectories(self.directory)
                self._trajectories = Changes(trajectories)
            except FileNotFoundError:
                self.lost_trajectories = True

    @property
    def rows(self) -> ChangedRows[Key]:
        return self._rows

    @rows.setter
    def rows(self, rows: Mapping[Key, dict[str, Any]]) -> None:
        self._rows = ChangedRows(rows, replaced=True)

    @property
    def trajectories(self) -> Changes[Key, Trajectory]:
        return self._trajectories

    @trajectories.setter
    def trajectories(self, trajectories: Mapping[Key, Trajectory]) -> None:
        self._trajectories = Changes(trajectories, replaced=True)

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

    def save(self, meta: dict[str, Any], clean: bool = False) -> None:
        """Commit what changed since the store was read or last saved, as new parts beside the
        stored ones, with the sidecar (`meta`, the schema version, the parts and the checksums).
        `clean` (the last save of a run) leaves no replaced or deleted entry in any part, so that a
        direct Parquet read sees each row once. The caller holds the store's writer lock
        (reports.store.lock)."""
        self.meta = {**meta, "schema_version": STORE_VERSION}
        tables: dict[str, Changes[Key, Any]] = {RESULTS: self._rows, TRAJECTORIES: self._trajectories}
        lost = {TRAJECTORIES} if self.lost_trajectories else set()
        plans = {
            name: plan_save(
                None if changes.replaced or name in lost else self.tables[name].parts,
                self.tables[name].members,
                changes,
                changes.changed,
                changes.removed,
                CAP[name],
                clean,
            )
            for name, changes in tables.items()
        }
        write = {RESULTS: self._write_rows, TRAJECTORIES: self._write_trajectories}
        writers = {
            f"{name}/{file}": (lambda path, w=write[name], k=keys: w(k, path))
            for name, plan in plans.items()
            for file, keys in plan.writes.items()
        }
        carried = {
            f"{name}/{p.file}": self.files[f"{name}/{p.file}"]
            for name, plan in plans.items()
            for p in plan.parts
            if p.file not in plan.writes
        }
        parts = {name: [p.to_json() for p in plan.parts] for name, plan in plans.items()}
        self.meta[PARTS] = parts
        self.files = store_files.commit(
            self.directory, writers, self.meta, carried, public=(RESULTS, TRAJECTORIES)
        )
        for name, changes in tables.items():
            self.tables[name] = self.tables[name].after(plans[name].parts, plans[name].writes, changes)
            changes.settle()
        self.lost_trajectories = False

    def _write_rows(self, keys: list[Key], path: Path) -> None:
        write_part(pd.DataFrame([self._rows[k] for k in keys], columns=list(COLUMNS)), path)

    def _write_trajectories(self, keys: list[Key], path: Path) -> None:
        _trajectory_frame({k: self._trajectories[k] for k in keys}).to_parquet(path, index=False)


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
    if target.name == RESULTS and not (target / SIDECAR).exists() and not (target / CURRENT).is_symlink():
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
    if meta.get("schema_version", 1) not in READS:
        versions = " and ".join(map(str, READS))
        raise damaged(root, f"schema version {meta['schema_version']}, this mbxval reads {versions}")
    return root, generation, meta, absent


def read_results(path: str | os.PathLike[str]) -> tuple[pd.DataFrame, dict[str, Any]]:
    """The rows (without the derived opt_ columns) and the sidecar of stored results, verified:
    StoreDamaged for files that do not match their checksums or rows that lack required columns."""
    frame, meta, _ = _read_rows(path)
    return frame, meta


def _read_rows(path: str | os.PathLike[str]) -> tuple[pd.DataFrame, dict[str, Any], StoredTable]:
    """The rows, the sidecar and what the generation holds of the rows' table."""
    root, generation, meta, absent = _committed(path)
    parts = listed_parts(root, meta, RESULTS)
    if parts is None:
        if RESULTS in absent or not (generation / RESULTS).is_file():
            raise damaged(root, f"{RESULTS} is missing")
        frames = [_checked(root, RESULTS, _read_file(root, generation / RESULTS, RESULTS))]
        frame, table = frames[0], StoredTable()
    else:
        try:
            frames = [
                _checked(root, f"{RESULTS}/{p.file}", f)
                for p, f in zip(parts, part_frames(root, generation, RESULTS, parts), strict=True)
            ]
        except FileNotFoundError as lost:
            raise damaged(root, str(lost).split(" has lost ")[-1] + " is missing") from None
        frame = live_rows(frames, parts, KEY)
        keys = [(str(a), str(b), str(c)) for a, b, c in zip(*(frame[k] for k in KEY), strict=True)]
        table = StoredTable(parts, members_of(keys, frame[PART_COLUMN].tolist(), parts))
        frame = frame.drop(columns=[PART_COLUMN])
        if len(frames) > 1:
            frame = frame.sort_values(list(KEY), kind="stable")
        frame = frame.reset_index(drop=True)
    for column in DECLARED:  # a column added since: absent from older files, NaN in older parts
        if column.name not in frame.columns:
            frame[column.name] = column.empty
        elif not _is_nan(column.empty) and frame[column.name].isna().any():
            frame[column.name] = frame[column.name].where(frame[column.name].notna(), column.empty)
    frame = frame[[c for c in COLUMNS if c in frame.columns]]
    return frame, meta, table


def missing_rows(meta: Mapping[str, Any], absent: set[str]) -> str | None:
    """The file of the rows a generation lists but lacks (its single file, or a part), or None."""
    if meta.get(PARTS) is None:
        return RESULTS if RESULTS in absent else None
    return next((n for n in sorted(absent) if n.startswith(f"{RESULTS}/")), None)


def _read_file(root: Path, file: Path, name: str) -> pd.DataFrame:
    try:
        return pd.read_parquet(file)
    except Exception as error:  # pyarrow's errors have no common base worth naming
        raise damaged(root, f"{name} cannot be read: {type(error).__name__}") from error


def _checked(root: Path, name: str, frame: pd.DataFrame) -> pd.DataFrame:
    """The rows of one file, refused when they lack a required column, a status or a key."""
    lacking = sorted(REQUIRED - set(frame.columns))
    if lacking:
        raise damaged(root, f"{name} lacks the columns {', '.join(lacking)}")
    if frame["status"].isna().any() or frame[list(KEY)].isna().any().any():
        raise damaged(root, f"{name} has rows without a status or key")
    return frame


def stored_truths(trajectories: Mapping[Key, Trajectory]) -> dict[str, Trajectory]:
    """The truth of each scenario among stored trajectories (the first stored, where there are more)."""
    found: dict[str, Trajectory] = {}
    for (scenario, engine, _), trajectory in trajectories.items():
        if engine == TRUTH:
            found.setdefault(scenario, trajectory)
    return found


def read_trajectories(path: str | os.PathLike[str]) -> dict[Key, Trajectory]:
    """Every stored trajectory by (scenario, engine, setting); the truth under engine TRUTH.
    FileNotFoundError when the store has lost its trajectories (a resume rebuilds them)."""
    return _read_trajectories(path)[0]


def _read_trajectories(path: str | os.PathLike[str]) -> tuple[dict[Key, Trajectory], StoredTable]:
    root, generation, meta, _ = _committed(path)
    parts = listed_parts(root, meta, TRAJECTORIES)
    if parts is None:
        file = generation / TRAJECTORIES
        if not file.is_file():
            raise FileNotFoundError(f"{root} has lost {TRAJECTORIES}")
        return _trajectories_of(_read_file(root, file, TRAJECTORIES)), StoredTable()
    stored: dict[Key, Trajectory] = {}
    homes: dict[Key, int] = {}
    for index, frame in enumerate(part_frames(root, generation, TRAJECTORIES, parts)):
        for key in parts[index].removed:
            stored.pop(key, None)
            homes.pop(key, None)
        found = _trajectories_of(frame)
        stored.update(found)
        homes.update(dict.fromkeys(found, index))
    return stored, StoredTable(parts, members_of(list(homes), list(homes.values()), parts))


def _trajectories_of(frame: pd.DataFrame) -> dict[Key, Trajectory]:
    stored: dict[Key, Trajectory] = {}
    for key, part in frame.groupby(list(KEY), sort=False):
        columns = part.drop(columns=list(KEY)).dropna(axis=1, how="all").reset_index(drop=True)
        stored[(str(key[0]), str(key[1]), str(key[2]))] = Trajectory.from_frame(columns)
    return stored


def _trajectory_frame(trajectories: dict[Key, Trajectory]) -> pd.DataFrame:
    """The trajectories one under another: the key columns, then every trajectory's columns in the
    order they first appear, NaN where a trajectory lacks one (what pd.concat of their frames gives,
    built from the arrays: a frame per trajectory and their concatenation cost milliseconds each)."""
    if not trajectories:
        return pd.DataFrame(columns=list(KEY))
    frames = [t.columns() for t in trajectories.values()]
    sizes = [len(t.times) for t in trajectories.values()]
    data: dict[str, Any] = {
        name: [key[i] for key, size in zip(trajectories, sizes, strict=True) for _ in range(size)]
        for i, name in enumerate(KEY)
    }
    for column in dict.fromkeys(c for f in frames for c in f):
        data[column] = np.concatenate(
            [
                np.asarray(f[column], dtype=float) if column in f else np.full(size, np.nan)
                for f, size in zip(frames, sizes, strict=True)
            ]
        )
    return pd.DataFrame(data)


def _is_nan(value: Any) -> bool:
    return isinstance(value, float) and math.isnan(value)
