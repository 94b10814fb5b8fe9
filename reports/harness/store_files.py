"""The files of a results store, changed together and verified on every load.

A store directory DIR holds its committed files in a generation, DIR/.generations/gNNNNNN/, and
`DIR/current` is a symbolic link to it; DIR/results.parquet, DIR/results.json and
DIR/trajectories.parquet are links through `current`, so the public paths never change (the
layout and its checks: reports.harness.store_layout). A save writes a complete new generation (the
data files, then the sidecar results.json with the SHA-256 and size of each), and then switches
`current` to it with one rename: a reader or a resume sees the old generation or the new one, never
a mix (SQLite's atomic commit, in files). Every load checks the checksums; a file that does not
match is damage, reported as such and never copied forward.

A save starts only on a store whose state is understood (store_layout.inspect): a missing or odd
`current`, or a generation whose sidecar does not account for its files, is refused with the
command that repairs it, and nothing is written or collected. After its switch a save keeps the
newest KEEP generations (the new one and the ones before it, each accounted for) and collects the
older ones; leftovers of interrupted saves (tmp-*) are removed. A store written before generations
(plain files in DIR) is read without checksums and converted by its next save.
"""

from __future__ import annotations

import json
import os
import shutil
import tempfile
from collections.abc import Callable, Iterable, Mapping
from pathlib import Path
from typing import Any

from reports.harness.store_layout import (
    CURRENT,
    GENERATIONS,
    SIDECAR,
    TEMPORARY,
    StoreDamaged,
    checksum,
    damaged,
    generation_names,
    inspect,
    number,
    read_sidecar,
    verify,
)

__all__ = ["CURRENT", "GENERATIONS", "SIDECAR", "StoreDamaged", "damaged", "read_sidecar", "verify"]

KEEP = 3  # generations kept after a save: the committed one and the two before it
Writer = Callable[[Path], object]


def committed(directory: str | os.PathLike[str]) -> Path | None:
    """The directory holding the committed files: the current generation, DIR itself for a store
    from before generations, or None for no store. StoreDamaged for a state not understood."""
    return inspect(directory).committed()


def commit(directory: str | os.PathLike[str], writers: Mapping[str, Writer], meta: Mapping[str, Any]) -> Path:
    """Write a new generation (each writer fills its file, then the sidecar with `meta` and the
    checksums) and make it the committed one. Nothing of it is left behind if this is interrupted
    before the switch; the old generation stays committed until then."""
    root = Path(directory)
    inspect(root).committed()  # refuses a store whose state is not understood, before any change
    home = root / GENERATIONS
    home.mkdir(parents=True, exist_ok=True)
    remove_leftovers(root, home)
    work = Path(tempfile.mkdtemp(prefix=TEMPORARY, dir=home))
    generation: Path | None = None
    switched = False
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
        generation = home / next_name(home)
        os.rename(work, generation)
        _sync(home)
        switch(root, generation)
        switched = True
        _sync(root)
    except BaseException:
        shutil.rmtree(work, ignore_errors=True)
        if generation is not None and not switched and generation.exists():
            _discard(generation)  # renamed but never committed: the old one stays current
        raise
    link_public(root, [*writers, SIDECAR])
    collect(home)
    return generation


def next_name(home: Path) -> str:
    names = generation_names(home)
    return f"g{(number(names[-1]) if names else 0) + 1:06d}"


def switch(root: Path, generation: Path) -> None:
    """Point `current` at the generation with one rename (the commit)."""
    temp = root / f".{CURRENT}.{os.getpid()}"
    temp.unlink(missing_ok=True)
    try:
        os.symlink(generation.relative_to(root), temp)
        os.replace(temp, root / CURRENT)
    except BaseException:
        temp.unlink(missing_ok=True)
        raise


def link_public(root: Path, names: Iterable[str]) -> None:
    """DIR/name -> current/name for each file (replacing a pre-generation plain file by rename)."""
    for name in names:
        path, target = root / name, Path(CURRENT) / name
        if path.is_symlink() and Path(os.readlink(path)) == target:
            continue
        temp = root / f".{name}.{os.getpid()}.link"
        temp.unlink(missing_ok=True)
        try:
            os.symlink(target, temp)
            os.replace(temp, path)
        except BaseException:
            temp.unlink(missing_ok=True)
            raise


def remove_leftovers(root: Path, home: Path) -> None:
    """Remove what interrupted saves left: unfinished generations and link temporaries."""
    for leftover in [*home.glob(f"{TEMPORARY}*"), *root.glob(f".{CURRENT}.*"), *root.glob(".*.link")]:
        if leftover.is_dir() and not leftover.is_symlink():
            shutil.rmtree(leftover, ignore_errors=True)
        else:
            leftover.unlink(missing_ok=True)


def collect(home: Path) -> None:
    """Keep the newest KEEP generations, collect the older ones (the caller has just committed the
    newest, on a store whose every generation was accounted for)."""
    for name in generation_names(home)[:-KEEP]:
        _discard(home / name)


def _discard(generation: Path) -> None:
    """Remove a generation: renamed out of sight first, so a reader never meets half of it."""
    gone = generation.parent / f"{TEMPORARY}gone-{generation.name}"
    os.rename(generation, gone)
    shutil.rmtree(gone, ignore_errors=True)


def sync_path(path: Path) -> None:
    """fsync a file, or a folder so that a rename in it is durable."""
    _sync(path)


def _sync(path: Path) -> None:
    fd = os.open(path, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)
