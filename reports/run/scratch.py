"""Private scratch directories in the system's temporary directory, and the sweep that removes the
ones a killed run left there.

A scratch directory is `mbxval-<kind>-<pid>-<random>` (tempfile.mkdtemp: private to the user), with
an OWNER file inside on which its maker holds an exclusive lock (flock) while it lives. It is
removed when its `scratch` context ends, by an exception, Ctrl-C or SIGTERM too; a run killed with
SIGKILL leaves it, and the next `scratch` of the same kind sweeps it: a directory is taken as
abandoned only when its lock can be taken (the lock dies with the process that held it), or, while
its maker has not yet made the lock, when the process named in its name no longer exists. A live
run's scratch is never removed, nor anything not named and made this way.
"""

from __future__ import annotations

import contextlib
import fcntl
import os
import re
import shutil
import stat
import tempfile
from collections.abc import Iterator
from pathlib import Path

OWNER = ".owner"
"""The lock file inside a scratch directory: held by the process using the directory."""


def _prefix(kind: str) -> str:
    return f"mbxval-{kind}-"


@contextlib.contextmanager
def scratch(kind: str) -> Iterator[str]:
    """A new private scratch directory `mbxval-<kind>-<pid>-...` in the system's temporary
    directory, locked by this process while in use and removed after; the abandoned ones of the
    same kind are swept first (`sweep`)."""
    sweep(kind)
    directory = tempfile.mkdtemp(prefix=f"{_prefix(kind)}{os.getpid()}-")
    try:
        with open(os.path.join(directory, OWNER), "w") as owner:  # close-on-exec: a spawned child
            fcntl.flock(owner, fcntl.LOCK_EX | fcntl.LOCK_NB)  # does not hold it
            yield directory
    finally:
        shutil.rmtree(directory, ignore_errors=True)


def sweep(kind: str) -> list[str]:
    """Remove the scratch directories of `kind` whose maker is gone; the names removed."""
    pattern = re.compile(re.escape(_prefix(kind)) + r"(\d+)-[A-Za-z0-9_]+$")
    removed = []
    root = Path(tempfile.gettempdir())
    with contextlib.suppress(OSError):
        for entry in os.scandir(root):
            found = pattern.match(entry.name)
            if found and _abandoned(Path(entry.path), int(found.group(1))):
                shutil.rmtree(entry.path, ignore_errors=True)
                removed.append(entry.name)
    return removed


def _abandoned(directory: Path, pid: int) -> bool:
    """Whether `directory` is a scratch directory of this user that no live process holds."""
    try:
        info = directory.lstat()
    except OSError:
        return False
    if not stat.S_ISDIR(info.st_mode) or info.st_uid != os.getuid():
        return False  # a link, a file, another user's: never ours to remove
    try:
        descriptor = os.open(directory / OWNER, os.O_RDONLY | os.O_NOFOLLOW)
    except FileNotFoundError:
        return not _alive(pid)  # its maker is between mkdtemp and the lock, or died there
    except OSError:
        return False
    try:
        fcntl.flock(descriptor, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError:
        return False  # held: in use
    finally:
        os.close(descriptor)
    return True


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True
