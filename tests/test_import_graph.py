"""The project's packages import cleanly one module at a time and their import graph has no cycle.

Each module is imported alone in a fresh process that holds none of our modules (so an import
that only works after another module happens to be loaded fails here): one interpreter loads the
third-party packages once and forks a child per module. The graph of imports between our own modules, read
from the source with `ast`, is searched for strongly connected components (issue 18).
"""

from __future__ import annotations

import ast
import pathlib
import subprocess
import sys

import adapters
from tests.support.engines import ENGINES

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


THIRD_PARTY = (
    "numpy", "scipy.integrate", "scipy.interpolate", "scipy.linalg", "scipy.optimize", "pandas",
    "pyarrow.parquet", "numba", "mujoco", "exudyn", "pinocchio", "matplotlib.pyplot", "tqdm",
    "dask", "distributed",
)  # fmt: skip
"""Loaded once before the forks: the cost of a fresh interpreter is theirs, not our modules'."""
FORKING_IMPORTER = """
import importlib, os, sys, traceback
import matplotlib
matplotlib.use("Agg")
for package in sys.argv[1].split(","):
    importlib.import_module(package)
assert not any(m.split(".")[0] in sys.argv[2].split(",") for m in sys.modules), "ours preloaded"
for name in sys.argv[3:]:
    pid = os.fork()
    if pid == 0:
        try:
            importlib.import_module(name)
        except BaseException:
            print(name + ": " + traceback.format_exc().strip().splitlines()[-1], flush=True)
            os._exit(1)
        os._exit(0)
    _, status = os.waitpid(pid, 0)
    if status and not os.WIFEXITED(status):
        print(name + ": ended by signal", flush=True)
"""


def _of_an_engine_not_installed(name: str) -> bool:
    """A module of an optional engine's adapter whose package is not installed (Drake without its
    extra): it cannot import here, by design."""
    missing = [engine for engine in adapters.names() if engine not in ENGINES]
    return any(name == f"adapters.{engine}" or name.startswith(f"adapters.{engine}.") for engine in missing)


def test_every_module_imports_alone() -> None:
    """Every module imports in a process that has loaded none of ours (a `__main__` module runs its
    command by design and is left out, as are the modules of an engine not installed here)."""
    names = sorted(
        name
        for name in module_paths()
        if not name.endswith("__main__") and not _of_an_engine_not_installed(name)
    )
    done = subprocess.run(
        [sys.executable, "-c", FORKING_IMPORTER, ",".join(THIRD_PARTY), ",".join(PACKAGES), *names],
        capture_output=True,
        text=True,
        cwd=ROOT,
        check=False,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout.splitlines() == []


def test_a_module_that_needs_another_loaded_first_fails_alone(tmp_path: pathlib.Path) -> None:
    """The check itself: a module that works only once another has been imported is reported."""
    (tmp_path / "pkg").mkdir()
    (tmp_path / "pkg" / "__init__.py").write_text("")
    (tmp_path / "pkg" / "a.py").write_text("import sys\nVALUE = 1\n")
    (tmp_path / "pkg" / "b.py").write_text("import sys\nVALUE = sys.modules['pkg.a'].VALUE\n")
    done = subprocess.run(
        [sys.executable, "-c", FORKING_IMPORTER, "numpy", "pkg", "pkg.a", "pkg.b"],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        check=False,
    )
    assert done.stdout.splitlines() == ["pkg.b: KeyError: 'pkg.a'"]


def test_package_import_graph_has_no_cycle() -> None:
    paths = module_paths()
    known = set(paths)
    graph = {name: imported(path, name, known) for name, path in paths.items()}
    assert cycles(graph) == []
