"""The layout of a results store on disk, and what a store's directory holds, in words.

A store DIR keeps each save as a generation DIR/.generations/gNNNNNN/ (the data files and the
sidecar results.json with their sizes and SHA-256), `DIR/current` is a symbolic link to the
committed one, and the public names DIR/results.parquet etc. are links through `current`.
`inspect` reads that layout without changing anything and names what it does not understand: a
missing `current` beside generations, a `current` that is a regular file, a directory (a copy made
with `cp -rL`), a dangling link or one out of .generations, or a generation whose sidecar does not
account for its files. Such a store is refused by readers and writers alike, with the command that
repairs it (reports.store.repair), so that nothing is taken as empty and collected.
"""

from __future__ import annotations

import hashlib
import json
import os
import re
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from scenarios.files.bounded_read import MiB, read_bounded_text

SCHEMA_VERSION = 1
"""The rows' schema (the gate's baselines share it)."""
GENERATIONS, CURRENT, SIDECAR = ".generations", "current", "results.json"
PLAIN = "results.parquet"  # a plain rows table in DIR that no generation holds: a layout not read
GENERATION = re.compile(r"g\d{6,}")
TEMPORARY = "tmp-"  # an unfinished save, or a generation being collected: never read
QUARANTINE = "quarantine-"  # what repair moved aside: never read, never collected


class StoreDamaged(Exception):
    """A store whose files do not match their checksums or each other; the message says what to do
    and `what` says what is wrong."""

    def __init__(self, message: str, what: str = "") -> None:
        super().__init__(message)
        self.what = what or message


def damaged(directory: Path, what: str) -> StoreDamaged:
    return StoreDamaged(
        f"the results store {directory} is damaged ({what}); it was left as it is: "
        f"run `mbxval store repair {directory}`, or move it aside and run again, or pass another --out",
        what,
    )


def not_understood(directory: Path, what: str) -> StoreDamaged:
    return StoreDamaged(
        f"the results store {directory} is not in a state mbxval understands ({what}); "
        f"nothing was changed: run `mbxval store repair {directory}`",
        what,
    )


def number(name: str) -> int:
    return int(name[1:])


@dataclass(frozen=True)
class StoreState:
    """What a store directory holds: its generations (oldest first), the one `current` names, and
    what is not understood (None: all is)."""

    root: Path
    generations: tuple[str, ...]
    current: str | None
    problem: str | None

    def committed(self) -> Path | None:
        """The folder of the committed files, None for no store; StoreDamaged when the state is not
        understood."""
        if self.problem is not None:
            raise not_understood(self.root, self.problem)
        return None if self.current is None else self.root / GENERATIONS / self.current


def generation_names(home: Path) -> list[str]:
    if not home.is_dir():
        return []
    names = [p.name for p in home.iterdir() if GENERATION.fullmatch(p.name)]
    return sorted(names, key=number)


def inspect(directory: str | os.PathLike[str]) -> StoreState:
    """The state of the store in `directory`, read without changing anything."""
    root = Path(directory)
    generations = generation_names(root / GENERATIONS)
    current, problem = _current(root, generations)
    if problem is None:
        problem = next(filter(None, (_unaccounted(root, name) for name in generations)), None)
    if current is None and problem is None and (root / PLAIN).exists() and not (root / PLAIN).is_symlink():
        problem = f"{PLAIN} is a plain file that no generation holds"
    return StoreState(root, tuple(generations), current, problem)


def _current(root: Path, generations: list[str]) -> tuple[str | None, str | None]:
    """The generation `current` names, or what is wrong with `current`."""
    link = root / CURRENT
    if link.is_symlink():
        text = os.readlink(link)
        parts = Path(text).parts
        if Path(text).is_absolute() or len(parts) != 2 or parts[0] != GENERATIONS:
            return None, f"{CURRENT} points outside {GENERATIONS} (to {text})"
        if not GENERATION.fullmatch(parts[1]) or parts[1] not in generations:
            return None, f"{CURRENT} points to {text}, which is not a generation"
        return parts[1], None
    if link.is_dir():
        return None, f"{CURRENT} is a directory, not a link (a copy made with cp -rL?)"
    if link.exists():
        kind = "a regular file" if link.is_file() else "not a link"
        return None, f"{CURRENT} is {kind}"
    through = [p.name for p in _entries(root) if p.is_symlink() and os.readlink(p).startswith(CURRENT)]
    if through:
        return None, f"{CURRENT} is missing ({', '.join(sorted(through))} point through it)"
    if len(generations) == 1:
        return generations[0], None  # a first save stopped between its rename and its switch
    if generations:
        return None, f"{CURRENT} is missing beside {len(generations)} generations"
    return None, None


def _entries(root: Path) -> list[Path]:
    return list(root.iterdir()) if root.is_dir() else []


def _unaccounted(root: Path, name: str) -> str | None:
    """Why a generation's sidecar does not account for its files (unreadable, or a size that
    differs), or None. Sizes only: the checksums are read where the files are (a load, a repair)."""
    generation = root / GENERATIONS / name
    try:
        meta = read_sidecar(generation, root)
        files = meta.get("files")
        if not isinstance(files, dict):
            return f"generation {name}: {SIDECAR} lists no checksums"
        for file, expected in files.items():
            path = generation / file
            recorded = expected.get("bytes") if isinstance(expected, dict) else None
            if path.is_file() and path.stat().st_size != recorded:
                return f"generation {name}: {file} does not have the size its {SIDECAR} records"
    except (StoreDamaged, FileNotFoundError):
        if not generation.exists():  # collected by the writer meanwhile
            return None
        return f"generation {name}: its {SIDECAR} is missing or cannot be read"
    return None


MAX_SIDECAR_BYTES = 64 * MiB
"""A generation's results.json (machine, versions, checksums: a few kB)."""


def read_sidecar(generation: Path, root: Path) -> dict[str, Any]:
    """The sidecar of a generation."""
    path = generation / SIDECAR
    if not path.is_file():
        raise damaged(root, f"{SIDECAR} is missing")
    try:
        meta = json.loads(read_bounded_text(path, MAX_SIDECAR_BYTES, "results sidecar"))
    except (OSError, ValueError) as error:  # FileRefused among them
        raise damaged(root, f"{SIDECAR} cannot be read: {str(error)[:300]}") from None
    except RecursionError:
        raise damaged(root, f"{SIDECAR} cannot be read: nested too deeply") from None
    if not isinstance(meta, dict):
        raise damaged(root, f"{SIDECAR} is not a JSON object")
    return meta


def verify(generation: Path, root: Path, meta: Mapping[str, Any]) -> set[str]:
    """Check every file the sidecar lists against its size and SHA-256; returns the listed files
    that are absent (the caller decides which may be rebuilt). Raises StoreDamaged on a mismatch."""
    files = meta.get("files")
    if files is None:
        raise damaged(root, f"{SIDECAR} lists no checksums")
    if not isinstance(files, dict):
        raise damaged(root, f"{SIDECAR} has a malformed file list")
    absent = set()
    for name, expected in files.items():
        path = generation / name
        if not path.is_file():
            absent.add(name)
            continue
        size, digest = checksum(path)
        if not isinstance(expected, dict) or (size, digest) != (
            expected.get("bytes"),
            expected.get("sha256"),
        ):
            raise damaged(root, f"{name} does not match its checksum")
    return absent


def checksum(path: Path) -> tuple[int, str]:
    digest, size = hashlib.sha256(), 0
    with path.open("rb") as stream:
        while block := stream.read(1 << 20):
            digest.update(block)
            size += len(block)
    return size, digest.hexdigest()
