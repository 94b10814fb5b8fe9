"""Write an output file whole or not at all, and only onto a regular file.

The content goes to a temporary file in the target's folder, is synced, and replaces the target
with one rename; an exception (a full disk, Ctrl-C, SIGTERM) removes the temporary file and leaves
the old target as it was. The target must be a regular file or absent: a device, a FIFO, a socket
or a directory is refused before anything is written. A symbolic link is written through, as shell
redirection does: the link stays and the file it points to is replaced. A new file's mode follows
the umask (0666 masked, like any file a user creates); an existing file keeps its mode.

A process killed outright (kill -9, a power cut) cannot remove its temporary file: the next write
to the same folder removes those of our naming (`.<target>.<pid>.<hex>.tmp`) that are older than
STALE_SECONDS and whose writer, the pid in the name, is no longer running (`remove_stale`).
"""

from __future__ import annotations

import contextlib
import os
import re
import secrets
import stat
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import IO


class OutputRefused(OSError):
    """The output path is not a regular file (or its folder does not exist); nothing was written."""


def output_target(path: str | os.PathLike[str]) -> Path:
    """The file a write to `path` replaces (the end of its symbolic links), checked: OutputRefused
    when it exists and is not a regular file, or when its folder does not exist."""
    given = Path(path)
    target = Path(os.path.realpath(given))
    try:
        mode = os.stat(target).st_mode
    except FileNotFoundError:
        mode = None
    except OSError as error:
        raise OutputRefused(f"output path {given} cannot be examined: {error.strerror}") from None
    if mode is not None and not stat.S_ISREG(mode):
        through = f" (a link to {target})" if target != given.absolute() else ""
        raise OutputRefused(
            f"output path {given}{through} is {_kind(mode)}, not a regular file; nothing was written"
        )
    if not target.parent.is_dir():
        raise OutputRefused(f"output directory {given.parent} does not exist")
    return target


def _kind(mode: int) -> str:
    kinds = {
        stat.S_ISDIR: "a directory",
        stat.S_ISFIFO: "a FIFO",
        stat.S_ISCHR: "a character device",
        stat.S_ISBLK: "a block device",
        stat.S_ISSOCK: "a socket",
    }
    return next((name for test, name in kinds.items() if test(mode)), "not a regular file")


@contextmanager
def atomic_path(path: str | os.PathLike[str]) -> Iterator[Path]:
    """A temporary path beside the target for any writer (an engine's own save function); when the
    block ends without an exception the file is synced and replaces the target."""
    target = output_target(path)
    try:
        keep = stat.S_IMODE(os.stat(target).st_mode)
    except FileNotFoundError:
        keep = None
    remove_stale(target.parent)
    temp = target.parent / f".{target.name}.{os.getpid()}.{secrets.token_hex(4)}.tmp"
    try:  # from its creation on: a signal arriving just after os.open still removes it
        try:
            fd = os.open(temp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666)  # the umask applies
        except FileExistsError:  # another writer's temporary file, by chance of the name
            raise OutputRefused(f"a temporary file {temp} is in the way; try again") from None
        os.close(fd)
        if keep is not None:
            os.chmod(temp, keep)
        yield temp
        sync_file(temp)
        os.replace(temp, target)
        sync_file(target.parent)
    except OutputRefused:
        raise
    except BaseException:
        temp.unlink(missing_ok=True)
        raise


STALE_SECONDS = 60.0
"""A temporary file younger than this is never removed: its writer may be between creating it and
writing its first byte."""
TEMPORARY = re.compile(r"\..+?\.(?:(\d+)\.)?[0-9a-f]{8}\.tmp")
"""Our temporary files' names: `.<target>.<pid>.<8 hex>.tmp`, or without the pid as written before
it was named."""


def remove_stale(folder: Path) -> None:
    """Remove the temporary files of our naming in `folder` left by writers that died: older than
    STALE_SECONDS, and with a writer's pid that no longer runs (or none). Best effort: a folder or
    file that cannot be read or removed is left."""
    now = time.time()
    with contextlib.suppress(OSError), os.scandir(folder) as entries:
        for entry in entries:
            found = TEMPORARY.fullmatch(entry.name)
            if found is None or not entry.is_file(follow_symlinks=False):
                continue
            with contextlib.suppress(OSError):
                old = now - entry.stat(follow_symlinks=False).st_mtime > STALE_SECONDS
                if old and not (found.group(1) and _running(int(found.group(1)))):
                    os.unlink(entry.path)


def _running(pid: int) -> bool:
    """Whether a process `pid` exists (another user's counts: it cannot be signalled, but runs)."""
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OverflowError):
        return True
    return True


@contextmanager
def atomic_output(path: str | os.PathLike[str], mode: str = "w") -> Iterator[IO[str]]:
    """A stream whose content replaces `path` only when the block ends without an exception."""
    with atomic_path(path) as temp, open(temp, mode, encoding="utf-8") as stream:
        yield stream


def write_text(path: str | os.PathLike[str], text: str) -> None:
    """Replace `path` with `text` (UTF-8) in one step: readers see the old file or the new one."""
    with atomic_output(path) as stream:
        stream.write(text)


def sync_file(path: Path) -> None:
    """fsync a file or a folder (a folder: so that a rename in it is durable)."""
    fd = os.open(path, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)
