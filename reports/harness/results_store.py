"""Stored results: tidy rows in results.parquet, a JSON sidecar results.json, and the trajectories
the report draws (each engine's default-setting run and the reference truth) in trajectories.parquet.

One row per run, keyed by (scenario, engine, setting). Every file is replaced whole, so an
interrupted sweep leaves the rows stored so far, and a resumed sweep skips them.
"""

from __future__ import annotations

import json
import math
import os
import tempfile
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import Any

import pandas as pd

from reports.harness.columns import COLUMNS
from scenarios.trajectory import Trajectory

SCHEMA_VERSION = 1
RESULTS, SIDECAR, TRAJECTORIES = "results.parquet", "results.json", "trajectories.parquet"
KEY = ("scenario", "engine", "setting")
TRUTH = "truth"
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
        if not fresh and (self.directory / RESULTS).exists():
            frame, self.meta = read_results(self.directory)
            self.rows = {key_of(r): r for r in frame.to_dict("records")}
            self.trajectories = read_trajectories(self.directory)

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
        """Write every file of the store (the sidecar gets `meta` plus the schema version)."""
        self.directory.mkdir(parents=True, exist_ok=True)
        self.meta = {**meta, "schema_version": SCHEMA_VERSION}
        _write(self.directory / RESULTS, lambda path: self.frame().to_parquet(path, index=False))
        trajectories = _trajectory_frame(self.trajectories)
        _write(self.directory / TRAJECTORIES, lambda path: trajectories.to_parquet(path, index=False))
        text = json.dumps(self.meta, indent=2, sort_keys=True, default=str)
        _write(self.directory / SIDECAR, lambda path: Path(path).write_text(text + "\n"))


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
    if target.is_file():
        target = target.parent
    if not (target / RESULTS).is_file():
        raise FileNotFoundError(f"no {RESULTS} in {target}")
    return target


def read_results(path: str | os.PathLike[str]) -> tuple[pd.DataFrame, dict[str, Any]]:
    """The rows (without the derived opt_ columns) and the sidecar of stored results."""
    directory = results_directory(path)
    frame = pd.read_parquet(directory / RESULTS)
    frame = frame[[c for c in COLUMNS if c in frame.columns]]
    sidecar = directory / SIDECAR
    meta = json.loads(sidecar.read_text()) if sidecar.is_file() else {}
    if meta.get("schema_version", SCHEMA_VERSION) != SCHEMA_VERSION:
        raise ValueError(f"{sidecar} has schema version {meta['schema_version']}, expected {SCHEMA_VERSION}")
    return frame, meta


def read_trajectories(path: str | os.PathLike[str]) -> dict[Key, Trajectory]:
    """Every stored trajectory by (scenario, engine, setting); the truth under engine TRUTH."""
    file = results_directory(path) / TRAJECTORIES
    if not file.is_file():
        return {}
    frame = pd.read_parquet(file)
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


def _write(path: Path, writer: Callable[[str], object]) -> None:
    fd, temp = tempfile.mkstemp(prefix=f".{path.name}.", dir=path.parent)
    os.close(fd)
    os.chmod(temp, 0o644)
    try:
        writer(temp)
        os.replace(temp, path)
    except BaseException:
        Path(temp).unlink(missing_ok=True)
        raise
