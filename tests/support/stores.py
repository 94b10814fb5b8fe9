"""Results stores edited as the store itself commits them, for tests of what reads them."""

from __future__ import annotations

import json
import shutil
from collections.abc import Callable, Iterable
from pathlib import Path

import pandas as pd

from reports.store.columns import WALL_COLUMNS
from reports.store.results_store import ResultsStore, key_of, read_results

RUN_TIMES = ("build_time", "run_time", "warmup_time", "repeats_time", *(c.name for c in WALL_COLUMNS))
"""The columns a run's clocks fill: never the same in two runs of one setting."""
WHERE_AND_WHEN = ("recorded_at", "host", "workers")
"""The columns that say when, on which machine and with how many workers a row was made."""


def doctor(source: Path, target: Path, edit: Callable[[pd.DataFrame], None]) -> Path:
    """A copy of the results with rows edited and committed as the store commits them (an edit of
    the file alone is refused as damage: see tests/reports/test_reliability.py)."""
    shutil.copytree(source, target, symlinks=True)
    store = ResultsStore(target)
    frame, _ = read_results(target)
    edit(frame)
    store.rows = {key_of(r): r for r in frame.to_dict("records")}
    store.save(store.meta)
    return target


def table_files(folder: Path, table: str) -> list[Path]:
    """The data files of a stored table in a generation (or a store's directory): its parts, or
    the single file a store from before parts holds."""
    path = folder / table
    return sorted(path.resolve().iterdir()) if path.is_dir() else [path.resolve()]


def copy_entry(source: Path, target: Path) -> None:
    """Copy a store's public entry as a copy that follows links makes it: a file, or a folder."""
    if source.is_dir():
        shutil.copytree(source, target)
    else:
        shutil.copy(source, target)


def write_schema_1(directory: Path, source: Path, without: Iterable[str] = ()) -> Path:
    """The rows and trajectories of the store `source` written as the mbxval before parts wrote
    them (no parts): one results.parquet (every row, sorted by key, with the opt_ columns, but the
    columns `without`, as a store from before they existed) and one trajectories.parquet, in a
    generation with the checksums in its sidecar, `current` and the public links."""
    from reports.store.layout import checksum
    from reports.store.results_store import _trajectory_frame, read_trajectories, rows_frame

    frame, meta = read_results(source)
    meta = {k: v for k, v in meta.items() if k not in ("files", "parts")} | {"schema_version": 1}
    folder = directory / ".generations" / "g000001"
    folder.mkdir(parents=True)
    rows = rows_frame(frame.to_dict("records"))
    rows.drop(columns=list(without)).to_parquet(folder / "results.parquet", index=False)
    _trajectory_frame(read_trajectories(source)).to_parquet(folder / "trajectories.parquet", index=False)
    names = ("results.parquet", "trajectories.parquet")
    meta["files"] = {n: dict(zip(("bytes", "sha256"), checksum(folder / n), strict=True)) for n in names}
    (folder / "results.json").write_text(json.dumps(meta, indent=2, sort_keys=True, default=str) + "\n")
    (directory / "current").symlink_to(Path(".generations") / "g000001")
    for name in ("results.parquet", "results.json", "trajectories.parquet"):
        (directory / name).symlink_to(Path("current") / name)
    return directory
