"""The files of a results store, changed together and verified on every load.

A store directory DIR holds its committed files in a generation, DIR/.generations/gNNNNNN/, and
`DIR/current` is a symbolic link to it; DIR/results.parquet, DIR/results.json and
DIR/trajectories.parquet are links through `current`, so the public paths never change. A save
writes a complete new generation (the data files, then the sidecar results.json with the SHA-256
and size of each), and then switches `current` to it with one rename: a reader or a resume sees
the old generation or the new one, never a mix (SQLite's atomic commit, in files). Every load
checks the checksums; a file that does not match is damage, reported as such and never copied
forward. The previous generation is kept (a reader that resolved it just before a switch can still
read it); older ones and the leftovers of interrupted saves are removed by the next save.

A store written before generations (plain files in DIR) is read without checksums and converted
by its next save.
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import tempfile
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

GENERATIONS, CURRENT, SIDECAR = ".generations", "current", "results.json"
Writer = Callable[[Path], object]


class StoreDamaged(Exception):
    """A store whose files do not match their checksums or each other; the message says what to do."""


def damaged(directory: Path, what: str) -> StoreDamaged:
    return StoreDamaged(
        f"the results store {directory} is damaged ({what}); it was left as it is: "
        "move it aside (or delete it) and run again, or pass another --out"
    )


def committed(directory: str | os.PathLike[str]) -> Path | None:
    """The directory holding the committed files: the current generation, DIR itself for a store
    from before generations, or None for no store."""
    root = Path(directory)
    link = root / CURRENT
    if link.is_symlink():
        target = root / os.readlink(link)
        if not target.is_dir():
            raise damaged(root, f"{CURRENT} points to the missing {target.name}")
        return target
    return root if (root / "results.parquet").is_file() else None


def read_sidecar(generation: Path, root: Path) -> dict[str, Any]:
    """The sidecar of a generation ({} when a pre-generation store has none)."""
    path = generation / SIDECAR
    if not path.is_file():
        if generation != root:
            raise damaged(root, f"{SIDECAR} is missing")
        return {}
    try:
        meta = json.loads(path.read_text())
    except (OSError, ValueError) as error:
        raise damaged(root, f"{SIDECAR} cannot be read: {error}") from error
    if not isinstance(meta, dict):
        raise damaged(root, f"{SIDECAR} is not a JSON object")
    return meta


def verify(generation: Path, root: Path, meta: Mapping[str, Any]) -> set[str]:
    """Check every file the sidecar lists against its size and SHA-256; returns the listed files
    that are absent (the caller decides which may be rebuilt). Raises StoreDamaged on a mismatch."""
    files = meta.get("files")
    if files is None:
        if generation != root:
            raise damaged(root, f"{SIDECAR} lists no checksums")
        return set()  # a store from before checksums
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


def commit(directory: str | os.PathLike[str], writers: Mapping[str, Writer], meta: Mapping[str, Any]) -> Path:
    """Write a new generation (each writer fills its file, then the sidecar with `meta` and the
    checksums) and make it the committed one. Nothing of it is left behind if this is interrupted
    before the switch; the old generation stays committed until then."""
    root = Path(directory)
    home = root / GENERATIONS
    home.mkdir(parents=True, exist_ok=True)
    _collect(root, home)
    work = Path(tempfile.mkdtemp(prefix="tmp-", dir=home))
    try:
        files = {}
        for name, write in writers.items():
            write(work / name)
            _sync(work / name)
            size, digest = checksum(work / name)
            files[name] = {"bytes": size, "sha256": digest}
        text = json.dumps({**meta, "files": files}, indent=2, sort_keys=True, default=str)
        (work / SIDECAR).write_text(text + "\n")
        _sync(work / SIDECAR)
        os.chmod(work, 0o755)
        generation = home / _next_name(home)
        os.rename(work, generation)
        _sync(home)
        _switch(root, generation)
    except BaseException:
        shutil.rmtree(work, ignore_errors=True)
        raise
    _link_public(root, [*writers, SIDECAR])
    _collect(root, home)
    return generation


def _next_name(home: Path) -> str:
    numbers = [int(p.name[1:]) for p in home.glob("g*") if p.name[1:].isdigit()]
    return f"g{max(numbers, default=0) + 1:06d}"


def _switch(root: Path, generation: Path) -> None:
    """Point `current` at the generation with one rename (the commit)."""
    temp = root / f".{CURRENT}.{os.getpid()}"
    temp.unlink(missing_ok=True)
    try:
        os.symlink(generation.relative_to(root), temp)
        os.replace(temp, root / CURRENT)
    except BaseException:
        temp.unlink(missing_ok=True)
        raise
    _sync(root)


def _link_public(root: Path, names: list[str]) -> None:
    """DIR/name -> current/name for each file (replacing a pre-generation plain file by rename)."""
    for name in names:
        path, target = root / name, Path(CURRENT) / name
        if path.is_symlink() and Path(os.readlink(path)) == target:
            continue
        temp = root / f".{name}.{os.getpid()}.link"
        temp.unlink(missing_ok=True)
        os.symlink(target, temp)
        os.replace(temp, path)


def _collect(root: Path, home: Path) -> None:
    """Remove leftovers of interrupted saves and every generation but the current and previous."""
    current = Path(os.readlink(root / CURRENT)).name if (root / CURRENT).is_symlink() else None
    for leftover in [*home.glob("tmp-*"), *root.glob(f".{CURRENT}.*"), *root.glob(".*.link")]:
        if leftover.is_dir() and not leftover.is_symlink():
            shutil.rmtree(leftover, ignore_errors=True)
        else:
            leftover.unlink(missing_ok=True)
    done = sorted(p.name for p in home.glob("g*") if p.name[1:].isdigit())
    keep = {current} | ({done[done.index(current) - 1]} if current in done and done.index(current) else set())
    for name in done:
        if name not in keep:  # older, or written but never committed (interrupted before the switch)
            shutil.rmtree(home / name, ignore_errors=True)


def _sync(path: Path) -> None:
    fd = os.open(path, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)
