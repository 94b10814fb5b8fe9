"""numba's on-disk cache knows only the source file of each cached function, not the files of the
functions it calls; this guard drops the package's cached machine code whenever any of its sources
changed, so an edit to a kernel never runs stale code."""

from __future__ import annotations

import hashlib
from pathlib import Path


def refresh(package: Path) -> None:
    """Delete numba's cache files under package/__pycache__ unless they match the current sources."""
    digest = _digest(package)
    cache = package / "__pycache__"
    stamp = cache / "numba-sources.sha256"
    try:
        if stamp.read_text() == digest:
            return
    except OSError:
        pass
    try:
        cache.mkdir(exist_ok=True)
        for stale in (*cache.glob("*.nbi"), *cache.glob("*.nbc")):
            stale.unlink(missing_ok=True)
        stamp.write_text(digest)
    except OSError:
        pass  # a read-only checkout: numba then caches elsewhere (NUMBA_CACHE_DIR) or not at all


def _digest(package: Path) -> str:
    """SHA-256 over each source's name and its own SHA-256, in name order: text moved across the
    boundary of two files, or a file renamed, changes it (a digest of the joined sources did not)."""
    whole = hashlib.sha256()
    for source in sorted(package.glob("*.py")):
        whole.update(source.name.encode() + b"\0" + hashlib.sha256(source.read_bytes()).digest())
    return whole.hexdigest()
