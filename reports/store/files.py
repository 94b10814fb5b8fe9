"""The files of a results store, changed together and verified on every load.

A store directory DIR holds its committed files in a generation, DIR/.generations/gNNNNNN/, and
`DIR/current` is a symbolic link to it; DIR/results.parquet, DIR/results.json and
DIR/trajectories.parquet are links through `current`, so the public paths never change (the
layout and its checks: reports.store.layout). A save writes a complete new generation (the
data files, then the sidecar results.json with the SHA-256 and size of each), and then switches
`current` to it with one rename: a reader or a resume sees the old generation or the new one, never
a mix (SQLite's atomic commit, in files). Every load checks the checksums; a file that does not
match is damage, reported as such and never copied forward.

A save starts only on a store whose state is understood (layout.inspect): a missing or odd
`current`, or a generation whose sidecar does not account for its files, is refused with the
command that repairs it, and nothing is written or collected. After its switch a save keeps the
newest KEEP generations (the new one and the ones before it, each accounted for) and collects the
older ones; leftovers of interrupted saves (tmp-*) are removed.
"""

from __future__ import annotations

import errno
import json
import os
import shutil
import tempfile
from collections.abc import Callable, Iterable, Mapping
from pathlib import Path
from typing import Any

from reports.store.atomic_write import sync_file
from reports.store.layout import (
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
    """The directory holding the committed files (the current generation), or None for no store.
    StoreDamaged for a state not understood."""
    return inspect(directory).committed()


def commit(
    directory: str | os.PathLike[str],
    writers: Mapping[str, Writer],
    meta: Mapping[str, Any],
    carried: Mapping[str, Mapping[str, Any]] | None = None,
    public: Iterable[str] = (),
) -> dict[str, dict[str, Any]]:
    """Write a new generation and make it the committed one: each writer fills its file (a name
    may be inside a folder: `results.parquet/part-000007.parquet`), each `carried` file (with its
    recorded size and checksum) is linked from the committed generation unchanged, then the sidecar
    gets `meta` and every file's size and checksum. Nothing of it is left behind if this is
    interrupted before the switch; the old generation stays committed until then. Returns the
    files the sidecar lists. `public` names the links DIR/name -> current/name to make."""
    root = Path(directory)
    committed_now = inspect(root).committed()  # refuses a store not understood, before any change
    carried = dict(carried or {})
    if carried:
        _check_carried(root, committed_now, carried)
    home = root / GENERATIONS
    home.mkdir(parents=True, exist_ok=True)
    remove_leftovers(root, home)
    work = Path(tempfile.mkdtemp(prefix=TEMPORARY, dir=home))
    generation: Path | None = None
    switched = False
    try:
        files: dict[str, dict[str, Any]] = {}
        folders = sorted({Path(n).parent for n in [*writers, *carried]} - {Path(".")}, key=str)
        for folder in folders:
            (work / folder).mkdir(parents=True)
        for name, write in writers.items():
            write(work / name)
            sync_file(work / name)
            size, digest = checksum(work / name)
            files[name] = {"bytes": size, "sha256": digest}
        for name, recorded in carried.items():
            assert committed_now is not None
            _link_or_copy(committed_now / name, work / name)
            files[name] = dict(recorded)
        for folder in folders:
            sync_file(work / folder)
        text = json.dumps({**meta, "files": files}, indent=2, sort_keys=True, default=str)
        (work / SIDECAR).write_text(text + "\n")
        sync_file(work / SIDECAR)
        os.chmod(work, 0o755)
        generation = home / next_name(home)
        os.rename(work, generation)
        sync_file(home)
        switch(root, generation)
        switched = True
        sync_file(root)
    except BaseException:
        shutil.rmtree(work, ignore_errors=True)
        if generation is not None and not switched and generation.exists():
            _discard(generation)  # renamed but never committed: the old one stays current
        raise
    link_public(root, [*(public or writers), SIDECAR])
    collect(home)
    return files


def _check_carried(root: Path, committed_now: Path | None, carried: Mapping[str, Mapping[str, Any]]) -> None:
    """The files a save links unchanged must be those the committed generation lists, with the
    same checksums: the store was read from it (a writer holds the lock, so it cannot change)."""
    listed = (read_sidecar(committed_now, root).get("files") or {}) if committed_now is not None else {}
    for name, recorded in carried.items():
        if listed.get(name) != dict(recorded):
            raise damaged(root, f"{name} is not the file this save read (the store changed under it)")


def _link_or_copy(source: Path, target: Path) -> None:
    """A hard link (the file is shared by the generations that list it, never copied), or a copy
    where the file system has no hard links."""
    try:
        os.link(source, target)
    except OSError as error:
        if error.errno not in (errno.EPERM, errno.EXDEV, errno.EMLINK, errno.ENOTSUP, errno.EOPNOTSUPP):
            raise
        shutil.copy2(source, target)


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
    """DIR/name -> current/name for each file (replacing by rename a plain file a repair adopted)."""
    for name in names:
        path, target = root / name, Path(CURRENT) / name
        if path.is_symlink() and Path(os.readlink(path)) == target:
            continue
        temp = root / f".{name}.{os.getpid()}.link"
        temp.unlink(missing_ok=True)
        try:
            os.symlink(target, temp)
            if path.is_dir() and not path.is_symlink():  # a table's folder, copied: now committed
                _discard_folder(path)
            os.replace(temp, path)
        except BaseException:
            temp.unlink(missing_ok=True)
            raise


def _discard_folder(folder: Path) -> None:
    """Remove a plain folder whose files a committed generation holds (renamed first, so that a
    reader never meets half of it)."""
    gone = folder.parent / f".{folder.name}.{os.getpid()}.gone.link"
    os.rename(folder, gone)
    shutil.rmtree(gone, ignore_errors=True)


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


sync_path = sync_file
"""fsync a file, or a folder so that a rename in it is durable (atomic_write's)."""
