"""numba's on-disk cache knows only the source file of each cached function, not the files of the
functions it inlines or the module constants it freezes; this guard drops the package's cached
machine code whenever any source the kernels compile changed: the package's own modules and every
module of the project they import (the cam profiles, the solver's limits), so an edit to any of
them never runs stale code."""

from __future__ import annotations

import ast
import hashlib
from functools import lru_cache
from pathlib import Path


@lru_cache(maxsize=1)
def drop_stale_cache() -> None:
    """Drop numba's cached kernels where their sources changed, once a process: before numba first
    reads its cache, whichever kernels load first."""
    refresh(Path(__file__).parent)


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


def compiled_sources(package: Path) -> list[Path]:
    """The package's modules and the project's modules they import, in path order: every file whose
    text can reach the compiled kernels. A module is the project's when it resolves to a file under
    the folder that holds the package's top-level package."""
    root = _source_root(package)
    own = sorted(package.glob("*.py"))
    imported: set[Path] = set()
    for source in own:
        for name in _imported_modules(source):
            imported.update(_module_files(root, name))
    return sorted(set(own) | imported)


def _digest(package: Path) -> str:
    """SHA-256 over each source's path below the source root and its own SHA-256, in path order:
    text moved across the boundary of two files, or a file renamed, changes it."""
    root = _source_root(package)
    whole = hashlib.sha256()
    for source in compiled_sources(package):
        name = source.relative_to(root).as_posix()
        whole.update(name.encode() + b"\0" + hashlib.sha256(source.read_bytes()).digest())
    return whole.hexdigest()


def _source_root(package: Path) -> Path:
    """The folder holding the outermost package that contains `package`."""
    top = package
    while (top.parent / "__init__.py").exists():
        top = top.parent
    return top.parent


def _imported_modules(source: Path) -> set[str]:
    """Absolute module names imported by `source`; for `from X import a`, both X and X.a (a may be
    a module or a name in X)."""
    try:
        tree = ast.parse(source.read_bytes())
    except (OSError, SyntaxError, ValueError):
        return set()
    names: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            names.add(node.module)
            names.update(f"{node.module}.{alias.name}" for alias in node.names)
    return names


def _module_files(root: Path, name: str) -> list[Path]:
    """The file of module `name` under root (a module file or a package's __init__), if any."""
    base = root.joinpath(*name.split("."))
    return [path for path in (base.with_suffix(".py"), base / "__init__.py") if path.is_file()]
