"""One writer per results store: an OS file lock on DIR/.lock, held for the whole run.

The lock is `flock` on a file that also records who holds it (process id, host, command, start),
so a second writer can be told whom it is waiting for. The kernel drops the lock when its holder
dies, however it dies, so a killed run never leaves a store locked. Readers never take it: they
read the committed generation (see files), which a writer never changes in place.
"""

from __future__ import annotations

import fcntl
import json
import os
import socket
import sys
import time
from pathlib import Path
from types import TracebackType

from reports.store.provenance import now

LOCK = ".lock"
POLL = 0.2  # seconds between attempts while waiting


class StoreBusy(Exception):
    """Another process is writing the store; the message names it."""


class WriterLock:
    """`with WriterLock(directory, wait=False):` holds the store's writer lock or raises StoreBusy."""

    def __init__(self, directory: str | os.PathLike[str], wait: bool = False) -> None:
        self.directory, self.wait = Path(directory), wait
        self._fd: int | None = None
        self._made = False

    def __enter__(self) -> WriterLock:
        self._made = not self.directory.exists()
        self.directory.mkdir(parents=True, exist_ok=True)
        fd = os.open(self.directory / LOCK, os.O_RDWR | os.O_CREAT, 0o644)
        try:
            while True:
                try:
                    fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
                    break
                except BlockingIOError:
                    if not self.wait:
                        raise StoreBusy(
                            f"{self.directory} is being written by {holder(self.directory)}; "
                            "wait for it to end (or pass --wait), or use another --out"
                        ) from None
                    time.sleep(POLL)
            record = {"pid": os.getpid(), "host": socket.gethostname(), "command": " ".join(sys.argv)}
            os.ftruncate(fd, 0)
            os.pwrite(fd, json.dumps({**record, "since": now()}).encode(), 0)
        except BaseException:
            os.close(fd)
            raise
        self._fd = fd
        return self

    def __exit__(
        self, kind: type[BaseException] | None, error: BaseException | None, trace: TracebackType | None
    ) -> None:
        if self._fd is not None:
            if self._made and [p.name for p in self.directory.iterdir()] == [LOCK]:
                # a folder this lock made for a command that stored nothing (an unreachable
                # --cluster, bad input found late): leave no trace, while still holding the lock
                (self.directory / LOCK).unlink()
                self.directory.rmdir()
            os.close(self._fd)  # closing releases the flock; the file stays (removing it would race)
            self._fd = None


def holder(directory: str | os.PathLike[str]) -> str:
    """Who holds the lock, as recorded in the lock file, in words."""
    try:
        record = json.loads((Path(directory) / LOCK).read_text() or "{}")
    except (OSError, ValueError):
        record = {}
    if not record:
        return "another process"
    where = f"on {record.get('host')} since {record.get('since')}"
    return f"process {record.get('pid')} {where} ({record.get('command')})"
