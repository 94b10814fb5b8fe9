"""The layering rules the cross-validation rests on, read from the source (every import, at module
level or inside a function, found with `ast`; nothing is imported):

- an engine adapter never imports the reference solver, so that what it computes is independent of
  the solver it is compared with (`adapters/reference.py`, which presents that solver as one more
  engine, is the one exception);
- `scenarios` (the engine-neutral vocabulary, with the closed forms beside the families) needs nothing
  of ours: a closed form that called the solver would judge the solver by itself;
- `reference_solver` reads scenarios and nothing above them;
- `reports/render` reads a results store: everything a report shows (verdicts, branch checks,
  truths, labels) is decided when the run is made and stored, so no module of it imports the
  solver, an engine, the stress or dynamics cases, or rebuilds a scenario; of the store it
  names only the column declarations and the store's reader and writer (RENDER_READS).
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


RENDER_FORBIDDEN = (
    "reference_solver",
    "adapters",
    "reports.stress",
    "reports.dynamics",
    "reports.scoring",
    "reports.run",
    "reports.gate",
    "reports.store",
    "reports.suites",
    "scenarios",
)
"""What a module of reports/render never names (a dotted prefix), but RENDER_READS."""
RENDER_READS = {
    "reports.store.columns": "the column declarations, with what the measured columns mean",
    "reports.store.results_store": "the store's reader",
    "reports.store.atomic_write": "the page written whole or not at all",
    "scenarios.trajectory": "the stored trajectories' type",
}


def named_modules(source: str, module: str) -> set[str]:
    """The dotted modules a module names in its imports (relative ones resolved; `from a import b`
    names both `a` and `a.b`, since b may be a module)."""
    found: set[str] = set()
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            found |= {alias.name for alias in node.names}
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parts = module.split(".")[: -node.level]
                base = ".".join([*parts, base] if base else parts)
            found |= {base} | {f"{base}.{alias.name}" for alias in node.names}
    return found


def _under(name: str, prefix: str) -> bool:
    return name == prefix or name.startswith(f"{prefix}.")


def forbidden_in_render(name: str) -> bool:
    """Whether a module of reports/render may not name `name`."""
    return any(_under(name, f) for f in RENDER_FORBIDDEN) and not any(_under(name, r) for r in RENDER_READS)


def render_offenders() -> dict[str, set[str]]:
    """The modules of reports/render that name what a report must not compute with."""
    found = {}
    for path in modules("reports/render"):
        module = ".".join(path.relative_to(ROOT).with_suffix("").parts)
        bad = {n for n in named_modules(path.read_text(), module) if forbidden_in_render(n)}
        if bad:
            found[str(path.relative_to(ROOT))] = bad
    return found


def test_render_reads_stored_results_only() -> None:
    assert render_offenders() == {}


@pytest.mark.parametrize(
    ("source", "expected"),
    [
        ("from reports.stress.cases import CASES\n", {"reports.stress.cases", "reports.stress.cases.CASES"}),
        ("def f():\n    import adapters\n", {"adapters"}),
        ("from ..scoring import truth\n", {"reports.scoring", "reports.scoring.truth"}),
        ("from . import markup\n", {"reports.render", "reports.render.markup"}),
    ],
)
def test_the_render_rule_sees_every_kind_of_import(source: str, expected: set[str]) -> None:
    """A module-level, a function-level and a relative import are all resolved to what they name."""
    assert named_modules(source, "reports.render.page") == expected


def test_the_render_rule_is_not_vacuous() -> None:
    """A reading of the solver, an engine, the stress cases, a scenario's rebuilding or a harness
    module other than those RENDER_READS names is an offence; the declarations are not."""
    for name in ("reference_solver.residual", "adapters", "reports.stress.branch_check", "reports.dynamics"):
        assert forbidden_in_render(name), name
    for name in (
        "reports.scoring.truth",
        "reports.scoring.level_error",
        "reports.scoring.agreement",
        "scenarios",
    ):
        assert forbidden_in_render(name), name
    for name in ("reports.store.columns.LOST", "scenarios.trajectory.Trajectory", "reports.render.markup"):
        assert not forbidden_in_render(name), name


@pytest.mark.parametrize(
    ("source", "expected"),
    [
        ("def f():\n    from reference_solver.dynamics import simulate\n", {"reference_solver"}),
        ("import reports.scoring.truth as truth\n", {"reports"}),
        ("from . import geometry\n", {"adapters"}),
        ("import numpy\nfrom scipy import linalg\n", set()),
    ],
)
def test_the_reader_sees_every_kind_of_import(source: str, expected: set[str]) -> None:
    """The rules are not vacuous: an import inside a function, an aliased one and a relative one are
    all found (a relative import stays inside its own package)."""
    assert imports_of(source, "adapters") == expected
