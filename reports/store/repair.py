"""`mbxval store repair DIR`: bring a store whose state mbxval does not understand back to one it
does, keeping every generation whose checksums verify and deleting nothing it cannot account for.

What it does, in this order, each step said in one line:
- leftovers of interrupted saves (tmp-*, link temporaries) are removed: they were never committed;
- every generation is verified by its checksums; one that does not verify is moved aside to
  .generations/quarantine-<name>-<time>/ (never read, never collected), not deleted;
- `current` as a directory (a copy made with `cp -rL`) and plain files in DIR whose sidecar
  verifies are adopted as a new generation (the plain files copied into it first, so a repair
  stopped half-way loses nothing), or, when their checksums are those of a generation already
  there, replaced by links; what does not verify is moved aside;
- `current` as a regular file is moved aside; a link that is dangling or points out of
  .generations is removed (a link holds no data);
- a valid `current` is kept; otherwise it is pointed at the newest generation that verifies, and
  the public links are made again.
"""

from __future__ import annotations

import os
import shutil
import time
from pathlib import Path

import reports.store.files as store_files
from reports.store.layout import (
    CURRENT,
    GENERATIONS,
    QUARANTINE,
    SIDECAR,
    TEMPORARY,
    StoreDamaged,
    generation_names,
    number,
    read_sidecar,
    verify,
)
from reports.store.results_store import RESULTS, TRAJECTORIES, missing_rows, read_results

PUBLIC = (RESULTS, SIDECAR, TRAJECTORIES)


class Repair:
    """One repair of one store directory (the caller holds its writer lock); `lines` says what
    was done."""

    def __init__(self, directory: str | os.PathLike[str]) -> None:
        self.root = Path(directory)
        self.home = self.root / GENERATIONS
        self.stamp = time.strftime("%Y%m%dT%H%M%S")
        self.lines: list[str] = []
        self.good: dict[str, bytes] = {}  # verified generation -> its sidecar's bytes

    def run(self) -> list[str]:
        if not holds_a_store(self.root):
            raise FileNotFoundError(f"no results store at {self.root}")
        self.home.mkdir(exist_ok=True)
        store_files.remove_leftovers(self.root, self.home)
        for name in generation_names(self.home):
            self._check(name)
        current = self._current()
        self._adopt_plain_files()
        if current is None:
            current = self._point_current()
        store_files.link_public(self.root, PUBLIC)
        kept = ", ".join(sorted(self.good, key=number))
        done = "" if self.lines else "nothing to repair: "
        rows = len(read_results(self.root)[0])
        self.lines.append(f"{done}{CURRENT} -> {current} ({rows} rows); generations kept: {kept}")
        return self.lines

    def _check(self, name: str) -> None:
        why = unverifiable(self.home / name, self.root)
        if why is None:
            self.good[name] = (self.home / name / SIDECAR).read_bytes()
            for part in unlisted_parts(self.home / name):
                label = f"{name}-{part.parent.name}-{part.name}"
                self._aside(part, label, f"generation {name}: {part.parent.name}/{part.name} is not listed")
        else:
            self._aside(self.home / name, name, f"generation {name} does not verify ({why})")

    def _current(self) -> str | None:
        """The generation a valid `current` names (kept), else None after dealing with `current`."""
        link = self.root / CURRENT
        if link.is_symlink():
            parts = Path(os.readlink(link)).parts
            if len(parts) == 2 and parts[0] == GENERATIONS and parts[1] in self.good:
                return parts[1]
            target = os.readlink(link)
            self.lines.append(f"removed the link {CURRENT} -> {target} (no verified generation there)")
            link.unlink()
        elif link.is_dir():
            self._adopt(link, CURRENT, f"the directory {CURRENT} (a copy made with cp -rL?)")
        elif link.exists():
            self._aside(link, CURRENT, f"{CURRENT} is a regular file, not a link")
        return None

    def _adopt_plain_files(self) -> None:
        """Plain files where DIR's links belong (a copy that followed the links): adopted when
        their sidecar verifies them, else moved aside."""
        plain = [n for n in PUBLIC if (self.root / n).exists() and not (self.root / n).is_symlink()]
        if not plain:
            return
        folder = self.home / f"{TEMPORARY}adopt-{self.stamp}"  # copies: the originals stay until
        folder.mkdir()  # their generation is committed, so a repair stopped here loses nothing
        for name in plain:
            if (self.root / name).is_dir():  # a table's parts
                shutil.copytree(self.root / name, folder / name)
                for part in (folder / name).iterdir():
                    store_files.sync_path(part)
            else:
                shutil.copy2(self.root / name, folder / name)
            store_files.sync_path(folder / name)
        self._adopt(folder, "files", "the plain files in the store's directory")

    def _adopt(self, folder: Path, label: str, what: str) -> None:
        """A folder of a generation's files: a duplicate of a verified one is removed, a new one
        becomes the next generation, one that does not verify is moved aside."""
        why = unverifiable(folder, folder)
        if why is not None:
            self._aside(folder, label, f"{what}: not verified ({why})")
            return
        sidecar = (folder / SIDECAR).read_bytes()
        same = [name for name, text in self.good.items() if text == sidecar]
        if same:
            shutil.rmtree(folder)
            self.lines.append(f"{what}: the same checksums as {same[-1]}, replaced by a link")
            return
        name = store_files.next_name(self.home)
        os.rename(folder, self.home / name)
        self.good[name] = sidecar
        self.lines.append(f"{what}: verified, adopted as generation {name}")

    def _aside(self, path: Path, name: str, why: str) -> None:
        place, count = self.home / f"{QUARANTINE}{name}-{self.stamp}", 1
        while place.exists() or place.is_symlink():  # a second repair within the same second
            place, count = self.home / f"{QUARANTINE}{name}-{self.stamp}-{count}", count + 1
        os.rename(path, place)
        self.lines.append(f"{why}: moved aside to {place.relative_to(self.root)}, not deleted")

    def _point_current(self) -> str:
        if not self.good:
            raise StoreDamaged(
                f"no generation of the results store {self.root} verifies; nothing was deleted"
                + (f" ({'; '.join(self.lines)})" if self.lines else ""),
                "no generation verifies",
            )
        newest = max(self.good, key=number)
        store_files.switch(self.root, self.home / newest)
        store_files.sync_path(self.root)
        self.lines.append(f"pointed {CURRENT} at {newest}, the newest generation that verifies")
        return newest


def holds_a_store(directory: Path) -> bool:
    """Whether the directory holds anything of a store (so that a repair of another folder, or of
    a typo, changes nothing)."""
    names = (GENERATIONS, CURRENT, *PUBLIC)
    return directory.is_dir() and any((directory / n).exists() or (directory / n).is_symlink() for n in names)


def unverifiable(folder: Path, root: Path) -> str | None:
    """Why a generation's files do not verify against its sidecar's checksums, or None."""
    try:
        meta = read_sidecar(folder, root)
        if "files" not in meta:
            return f"{SIDECAR} lists no checksums"
        absent = verify(folder, root, meta)
    except (StoreDamaged, OSError) as error:
        return getattr(error, "what", str(error))
    missing = missing_rows(meta, absent)
    return None if missing is None else f"{missing} is missing"


def unlisted_parts(generation: Path) -> list[Path]:
    """Files in a verified generation's table folders that its sidecar does not list (never read)."""
    listed = set(read_sidecar(generation, generation.parent.parent).get("files") or {})
    folders = [generation / t for t in (RESULTS, TRAJECTORIES) if (generation / t).is_dir()]
    return sorted(p for f in folders for p in f.iterdir() if f"{f.name}/{p.name}" not in listed)
