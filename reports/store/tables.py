"""A stored table in the committed generation: its parts, or the single file an older mbxval
wrote; which entry of each key is live; and a part written so that the parts read as one dataset.

A generation with parts lists each table's parts in its sidecar, oldest first ("parts"), beside the
size and SHA-256 of every file ("files", as `table/part-NNNNNN.parquet`). Only listed parts are
read: a part file the sidecar does not list (a save stopped between writing its part and its
sidecar never commits such a generation, but a copy or a hand may leave one) is never read. The
newest entry of a key wins, and the keys a part lists as removed hide the entries of older parts.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import pandas as pd
import pyarrow as pa

from reports.store.changes import Changes
from reports.store.columns import COLUMNS, DECLARED
from reports.store.layout import damaged
from reports.store.parts import Key, Part

PARTS = "parts"  # the sidecar's list of each table's parts
PART_COLUMN = "__part"  # the part a row was read from, while it is resolved


@dataclass(frozen=True)
class StoredTable:
    """What the committed generation holds of one table: its parts (None: a single file of schema
    1, or a table lost, to be written whole by the next save) and the live keys of each part."""

    parts: tuple[Part, ...] | None = None
    members: dict[str, set[Key]] = field(default_factory=dict)

    def after(
        self, parts: tuple[Part, ...], writes: Mapping[str, list[Key]], changes: Changes[Key, Any]
    ) -> StoredTable:
        """What the generation a save just committed holds: the written parts' keys, and the kept
        parts' keys less those that changed or were removed."""
        moved = changes.changed | changes.removed
        members = {}
        for part in parts:
            if part.file in writes:
                members[part.file] = set(writes[part.file])
            else:
                kept = self.members.get(part.file, set())
                kept.difference_update(moved)  # in place: the cost of the batch, not of the part
                members[part.file] = kept
        return StoredTable(parts, members)


def listed_parts(root: Path, meta: Mapping[str, Any], table: str) -> tuple[Part, ...] | None:
    """The table's parts as the sidecar lists them, or None for a store from before parts (one file)."""
    listed = meta.get(PARTS)
    if listed is None:
        return None
    try:
        if not isinstance(listed, dict) or not isinstance(listed.get(table, []), list):
            raise ValueError("not a list of parts per table")
        parts = tuple(Part.from_json(p) for p in listed.get(table, []))
    except (ValueError, TypeError) as error:
        raise damaged(root, f"its sidecar's {PARTS} cannot be read: {error}") from None
    files = meta.get("files") or {}
    unlisted = [p.file for p in parts if f"{table}/{p.file}" not in files]
    if unlisted:
        raise damaged(root, f"{table}/{unlisted[0]} has no checksum in its sidecar")
    return parts


def part_frames(root: Path, folder: Path, table: str, parts: tuple[Part, ...]) -> list[pd.DataFrame]:
    """Each listed part read whole (FileNotFoundError for a part that is absent)."""
    frames = []
    for part in parts:
        path = folder / table / part.file
        if not path.is_file():
            raise FileNotFoundError(f"{root} has lost {table}/{part.file}")
        try:
            frames.append(pd.read_parquet(path))
        except Exception as error:  # pyarrow's errors have no common base worth naming
            raise damaged(root, f"{table}/{part.file} cannot be read: {type(error).__name__}") from error
    return frames


def hidden_before(parts: tuple[Part, ...]) -> dict[Key, int]:
    """For each removed key, the newest part that removed it: its entries in older parts are dead."""
    newest: dict[Key, int] = {}
    for index, part in enumerate(parts):
        for key in part.removed:
            newest[key] = index
    return newest


def live_rows(frames: list[pd.DataFrame], parts: tuple[Part, ...], key: tuple[str, ...]) -> pd.DataFrame:
    """The rows of the parts, one per key: the newest, unless a newer part removed it; each row
    tagged with its part's index in PART_COLUMN."""
    tagged = [f.assign(**{PART_COLUMN: i}) for i, f in enumerate(frames) if len(f)]
    if not tagged:
        first = frames[0] if frames else pd.DataFrame(columns=list(key))
        return first.assign(**{PART_COLUMN: pd.Series(dtype="int64")})
    frame = pd.concat(tagged, ignore_index=True) if len(tagged) > 1 else tagged[0]
    frame = frame.drop_duplicates(list(key), keep="last")
    hidden = hidden_before(parts)
    if hidden:
        columns = [frame[c].astype(str) for c in key]
        keep = [
            hidden.get((a, b, c), -1) <= p for a, b, c, p in zip(*columns, frame[PART_COLUMN], strict=True)
        ]
        frame = frame[keep]
    return frame


def members_of(keys: list[Key], indices: list[int], parts: tuple[Part, ...]) -> dict[str, set[Key]]:
    """The live keys of each part, from each live entry's key and part index."""
    members: dict[str, set[Key]] = {p.file: set() for p in parts}
    for key, index in zip(keys, indices, strict=True):
        members[parts[index].file].add(key)
    return members


EMPTY_TYPES = {str: pa.string(), bool: pa.bool_(), int: pa.int64(), float: pa.float64()}


def write_part(frame: pd.DataFrame, path: Path) -> None:
    """The rows as a part stores them: the declared columns (the opt_ columns of `rows_frame` are
    derived from `options` and not stored); a column without any value gets its declared column's
    type, so that the parts of a table read together as one dataset (`pd.read_parquet` of the
    folder)."""
    frame = frame[[c for c in COLUMNS if c in frame.columns]]
    empty = [c for c in frame.columns if frame[c].dtype == object and frame[c].isna().all()]
    if not empty:
        frame.to_parquet(path, index=False)
        return
    schema = pa.Schema.from_pandas(frame, preserve_index=False)
    for column in DECLARED:
        index = schema.get_field_index(column.name)
        if index >= 0 and pa.types.is_null(schema.field(index).type):
            kind = EMPTY_TYPES.get(type(column.empty), pa.string())
            schema = schema.set(index, pa.field(column.name, kind))
    frame.to_parquet(path, index=False, schema=schema)
