"""Reading a file that a user (or a pull request) names, within declared bounds.

Every file mbxval reads on a user's word (a scenario file, a spline profile's CSV, a trajectory for
`compare`, a baseline) is read here: a regular file only (a FIFO, a device such as /dev/zero, a socket
or a directory is refused at once, and opening never blocks on a FIFO), at most its declared size
(checked before reading, and the read itself stops one byte past it), as UTF-8 text. Messages name
the file and the limit, never its contents.
"""

from __future__ import annotations

import os
import stat
from pathlib import Path

MiB = 1024**2
MAX_SCENARIO_FILE_BYTES = 16 * MiB
"""A scenario file: far above any mechanism the limits of scenarios.limits let through."""
MAX_PROFILE_CSV_BYTES = 16 * MiB
"""A spline profile's table of radii."""
MAX_TRAJECTORY_CSV_BYTES = 512 * MiB
"""A trajectory for `compare`: about the CSV of the largest trajectory scenarios.limits allows."""
MAX_BASELINE_BYTES = 64 * MiB
"""A gate baseline (the default suite's is under 1 MiB)."""


class FileRefused(ValueError):
    """A file that is not read: not a regular file, over its size limit, or not UTF-8 text."""


def _kind(mode: int) -> str:
    kinds = (
        (stat.S_ISDIR, "a directory"),
        (stat.S_ISFIFO, "a FIFO"),
        (stat.S_ISSOCK, "a socket"),
        (stat.S_ISCHR, "a character device"),
        (stat.S_ISBLK, "a block device"),
    )
    return next((name for test, name in kinds if test(mode)), "not a regular file")


def read_bounded_text(path: str | os.PathLike[str], limit: int, what: str) -> str:
    """The UTF-8 text of the regular file at `path`, at most `limit` bytes; FileRefused otherwise
    (OSError where the file cannot be opened at all)."""
    flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOCTTY", 0)
    fd = os.open(path, flags)
    try:
        mode = os.fstat(fd).st_mode
        if not stat.S_ISREG(mode):
            raise FileRefused(f"{path}: {_kind(mode)}, not a regular file: a {what} must be a file")
        size = os.fstat(fd).st_size
        if size > limit:
            raise FileRefused(f"{path}: {size} bytes, over the {limit // MiB} MiB a {what} may have")
        chunks, total = [], 0
        while total <= limit:
            chunk = os.read(fd, min(limit + 1 - total, 4 * MiB))
            if not chunk:
                break
            chunks.append(chunk)
            total += len(chunk)
        if total > limit:
            raise FileRefused(f"{path}: over the {limit // MiB} MiB a {what} may have")
    finally:
        os.close(fd)
    try:
        return b"".join(chunks).decode("utf-8")
    except UnicodeDecodeError as error:
        raise FileRefused(f"{path}: not UTF-8 text (byte {error.start})") from None


def inside(folder: Path, name: str) -> Path:
    """The file `name` (relative to `folder`) resolved, links followed; FileRefused when it lies
    outside `folder`: a scenario file names data beside it, never elsewhere on the machine."""
    root = folder.resolve()
    target = (root / name).resolve()
    if not target.is_relative_to(root):
        shown = name if len(name) <= 200 else name[:200] + "..."
        raise FileRefused(
            f"{shown!r} lies outside the scenario file's folder {root}: files it names must be there"
        )
    return target
