"""numba's on-disk cache knows only the source file of each cached function, not the files of the
functions it calls; this guard drops the package's cached machine code whenever any of its sources
changed, so an edit to a kernel never runs stale code."""

from __future__ import annotations

import hashlib
from pathlib import Path


def refresh(package: Path) -> None:
    """Delete numba's cache files under package/__pycache__ unless they match the current sources."""
    digest = hashlib.sha256(b"".join(p.read_bytes() for p in sorted(package.glob("*.py")))).hexdigest()
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
