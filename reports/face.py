"""A package's face: the short list of names it offers other packages, each loaded from the module
that defines it on first use.

A face's `__init__` lists what it offers as re-exports under TYPE_CHECKING (`from
reports.store.lock import WriterLock as WriterLock`), so that a reader and the type checker see
where every name comes from, and hands attribute lookups to `load`. Nothing is
imported before it is asked for: the command line's start reads light names (a lock, a stop flag)
from the same faces as the heavy ones (the store's tables need pandas, the recordings the native
solver, the report its figures) and imports none of the heavy modules
(tests/reports/cli/test_imports_on_demand.py)."""

from __future__ import annotations

import ast
import functools
import importlib
import sys
from pathlib import Path


@functools.cache
def origins(package: str) -> dict[str, tuple[str, str]]:
    """Each name the face of `package` offers: the module it comes from and its name there, read
    from the face's TYPE_CHECKING imports."""
    tree = ast.parse(Path(str(sys.modules[package].__file__)).read_text())
    found: dict[str, tuple[str, str]] = {}
    for node in tree.body:
        if isinstance(node, ast.If) and isinstance(node.test, ast.Name) and node.test.id == "TYPE_CHECKING":
            for statement in node.body:
                if isinstance(statement, ast.ImportFrom) and statement.module:
                    for alias in statement.names:
                        found[alias.asname or alias.name] = (statement.module, alias.name)
    return found


def load(package: str, name: str) -> object:
    """The value of `name` on the face of `package`, imported now if it is not yet (AttributeError
    for a name the face does not offer)."""
    origin = origins(package).get(name)
    if origin is None:
        raise AttributeError(f"module {package!r} has no attribute {name!r}")
    module, attribute = origin
    if module == package:  # a part of the package offered whole, as a namespace
        value: object = importlib.import_module(f"{package}.{attribute}")
    else:
        value = getattr(importlib.import_module(module), attribute)
    setattr(sys.modules[package], name, value)
    return value
