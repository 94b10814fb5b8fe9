"""The mechanism drawings a run leaves beside its results (DIR/drawings/, written by
reports.drawing.files when the run is made), read for the report: the page shows them as stored and
never draws."""

from __future__ import annotations

import json
import os
from pathlib import Path

from reports.store import results_directory

DRAWINGS = "drawings"
"""The folder of a results directory that holds the drawings."""
INDEX = "index.json"
"""In that folder: {scenario name: its SVG file's name}."""
MAX_BYTES = 1 << 20
"""A drawing larger than this (1 MiB) is not embedded."""


def read_drawings(results: str | os.PathLike[str]) -> dict[str, str]:
    """{scenario: SVG text} of the drawings stored beside `results` (empty when there are none, or
    when the index cannot be read: a report never fails for want of a picture)."""
    try:
        folder = results_directory(results) / DRAWINGS
    except FileNotFoundError:  # no store there (yet): the folder as given
        folder = Path(results) / DRAWINGS
    found: dict[str, str] = {}
    for scenario, name in read_index(folder).items():
        path = folder / name
        try:
            if path.is_file() and not path.is_symlink() and path.stat().st_size <= MAX_BYTES:
                found[scenario] = path.read_text(encoding="utf-8")
        except OSError:
            continue
    return found


def read_index(folder: Path) -> dict[str, str]:
    """{scenario: bare file name} of a drawings folder's index; empty when it cannot be read. A name
    is reduced to its last part, so that it never reaches out of the folder."""
    try:
        index = json.loads((folder / INDEX).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return {}
    if not isinstance(index, dict):
        return {}
    return {str(scenario): Path(str(name)).name for scenario, name in index.items()}
