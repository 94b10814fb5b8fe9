"""The layering rules the cross-validation rests on, read from the source (every import, at module
level or inside a function, found with `ast`; nothing is imported):

- an engine adapter never imports the reference solver, so that what it computes is independent of
  the solver it is compared with (`adapters/reference.py`, which presents that solver as one more
  engine, is the one exception);
- `scenarios` (the engine-neutral vocabulary, with the closed forms beside the families) needs nothing
  of ours: a closed form that called the solver would judge the solver by itself;
- `reference_solver` reads scenarios and nothing above them.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
OURS = ("scenarios", "reference_solver", "adapters", "reports", "benchmarks")


def imports_of(source: str, package: str) -> set[str]:
    """The top-level packages of ours that a module of `package` imports, absolute or relative."""
    found: set[str] = set()
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            found |= {alias.name.split(".")[0] for alias in node.names}
        elif isinstance(node, ast.ImportFrom):
            found.add(package if node.level else (node.module or "").split(".")[0])
    return found & set(OURS)


def modules(package: str) -> list[Path]:
    return sorted((ROOT / package).rglob("*.py"))


def offenders(
    package: str, forbidden: set[str], allowed: frozenset[str] = frozenset()
) -> dict[str, set[str]]:
    """The modules of `package` (but `allowed`) that import one of `forbidden`, with what they import."""
    found = {}
    for path in modules(package):
        relative = str(path.relative_to(ROOT))
        if relative in allowed:
            continue
        bad = imports_of(path.read_text(), package) & forbidden
        if bad:
            found[relative] = bad
    return found


def test_engine_adapters_never_import_the_reference_solver() -> None:
    assert offenders("adapters", {"reference_solver"}, frozenset({"adapters/reference.py"})) == {}


def test_scenarios_and_closed_forms_import_nothing_of_ours() -> None:
    assert offenders("scenarios", set(OURS) - {"scenarios"}) == {}


def test_reference_solver_reads_only_scenarios() -> None:
    assert offenders("reference_solver", {"adapters", "reports", "benchmarks"}) == {}


@pytest.mark.parametrize(
    ("source", "expected"),
    [
        ("def f():\n    from reference_solver.dynamics import simulate\n", {"reference_solver"}),
        ("import reports.harness.truth as truth\n", {"reports"}),
        ("from . import geometry\n", {"adapters"}),
        ("import numpy\nfrom scipy import linalg\n", set()),
    ],
)
def test_the_reader_sees_every_kind_of_import(source: str, expected: set[str]) -> None:
    """The rules are not vacuous: an import inside a function, an aliased one and a relative one are
    all found (a relative import stays inside its own package)."""
    assert imports_of(source, "adapters") == expected
