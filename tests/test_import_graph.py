"""The project's packages import cleanly one module at a time and their import graph has no cycle.

Each module is imported alone in a fresh interpreter (so an import that only works after another
module happens to be loaded fails here), and the graph of imports between our own modules, read
from the source with `ast`, is searched for strongly connected components (issue 18).
"""

from __future__ import annotations

import ast
import os
import pathlib
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]
PACKAGES = ("scenarios", "reference_solver", "adapters", "reports")


def module_paths() -> dict[str, pathlib.Path]:
    """Every module of our packages, by dotted name."""
    found: dict[str, pathlib.Path] = {}
    for package in PACKAGES:
        for path in (ROOT / package).rglob("*.py"):
            name = ".".join(path.relative_to(ROOT).with_suffix("").parts)
            found[name.removesuffix(".__init__")] = path
    return found


def imported(path: pathlib.Path, name: str, known: set[str]) -> set[str]:
    """The modules of ours that `name` imports (absolute or relative, any depth)."""
    found: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            found |= {alias.name for alias in node.names}
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parts = name.split(".") if path.name == "__init__.py" else name.split(".")[:-1]
                parts = parts[: len(parts) - node.level + 1]
                base = ".".join(parts + ([base] if base else []))
            found.add(base)
            found |= {f"{base}.{alias.name}" for alias in node.names}
    return {module for module in found if module in known and module != name}


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components of more than one module (iterative Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    components: list[list[str]] = []
    for root in graph:
        if root in index:
            continue
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = len(index)
        stack.append(root)
        on_stack.add(root)
        while work:
            node, children = work[-1]
            child = next(children, None)
            if child is not None:
                if child not in index:
                    index[child] = low[child] = len(index)
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(sorted(graph[child]))))
                elif child in on_stack:
                    low[node] = min(low[node], index[child])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                component = []
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    component.append(member)
                    if member == node:
                        break
                if len(component) > 1:
                    components.append(sorted(component))
    return components


def test_cycle_search_finds_a_planted_cycle() -> None:
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}
    assert cycles(graph) == [["a", "b", "c"]]
    assert cycles({"a": {"b"}, "b": set()}) == []


@pytest.mark.slow  # one fresh interpreter per module, as many at once as there are cores
def test_every_module_imports_alone() -> None:
    """Every module imports in a fresh interpreter (a `__main__` module runs its command by design)."""
    names = sorted(name for name in module_paths() if not name.endswith("__main__"))

    def failure(name: str) -> str | None:
        done = subprocess.run(
            [sys.executable, "-c", f"import {name}"], capture_output=True, text=True, cwd=ROOT
        )
        return f"{name}: {(done.stderr.strip().splitlines() or ['?'])[-1]}" if done.returncode else None

    with ThreadPoolExecutor(max_workers=os.cpu_count() or 1) as pool:
        failed = [found for found in pool.map(failure, names) if found]
    assert failed == []


def test_package_import_graph_has_no_cycle() -> None:
    paths = module_paths()
    known = set(paths)
    graph = {name: imported(path, name, known) for name, path in paths.items()}
    assert cycles(graph) == []
