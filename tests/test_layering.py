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
  names only the column declarations, its reader and the atomic writer (RENDER_READS, STORE_READ);
- inside `reports`, each part (a package or a module) sits in one of REPORTS_LAYERS and imports only
  parts of the layers below it, so no arrow runs back up; the packages of every package of ours
  import each other without a cycle;
- a package of `reports` offers other packages a face, the names its `__init__` re-exports, and
  the modules of `reports` and `mbxval` import only that face, never a module behind it (benchmarks
  and tests may reach further: they time and test the parts).
"""

from __future__ import annotations

import ast
import graphlib
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
    "reports.store": "the store's face, of which a report names only STORE_READ",
    "scenarios.trajectory": "the stored trajectories' type",
}
"""What a module of reports/render may name (a dotted prefix)."""
STORE_READ = (
    *("CLOSED_FORM", "DRIFT_DEFINITION", "DRIFT_SERIES", "ERROR_SERIES", "FORCE_DEFINITION"),
    *("LEVEL_COLUMNS", "LOST", "NOT_RECORDED", "SCALE_DEFINITION", "WALL_COLUMNS", "Judgement"),
    *("Key", "TRUTH", "read_results", "read_trajectories", "results_directory"),
    "atomic_output",
)
"""Of the store's face, what a report reads: the column declarations, with what the measured columns
mean, the store's reader and the page written whole or not at all."""


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
    if name == "reports.store" or name in {f"reports.store.{read}" for read in STORE_READ}:
        return False
    return any(_under(name, f) for f in RENDER_FORBIDDEN) and not any(
        _under(name, r) for r in RENDER_READS if r != "reports.store"
    )


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
        "reports.store.WriterLock",
        "reports.store.columns",
        "scenarios",
    ):
        assert forbidden_in_render(name), name
    for name in ("reports.store.LOST", "scenarios.trajectory.Trajectory", "reports.render.markup"):
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


REPORTS_LAYERS = (
    ("face",),
    ("scoring",),
    ("store",),
    ("gate", "run", "dynamics", "stress", "render"),
    ("drawing", "suites"),
    ("cli",),
    ("entry",),
)
"""The parts of reports/ (its packages and modules), lowest first: scoring judges a trajectory, the
store keeps rows declared in its columns (which read what scoring's measures mean), the gate, the
runs, the two suites and the report stand on both, the suites' composition and the drawing above
those, the command line above everything, and `face` (how a package's face loads) below all."""
LAYER = {part: level for level, parts in enumerate(REPORTS_LAYERS) for part in parts}


def module_name(path: Path) -> str:
    return ".".join(path.relative_to(ROOT).with_suffix("").parts).removesuffix(".__init__")


def part_of(name: str, package: str = "reports") -> str | None:
    """The part of `package` (its direct subpackage or module) that the dotted `name` lies in."""
    parts = name.split(".")
    depth = package.count(".") + 1
    return parts[depth] if name.startswith(f"{package}.") and len(parts) > depth else None


def is_part(package: str, name: str | None) -> bool:
    """Whether `name` is a subpackage or a module of `package` (not a name defined in its face)."""
    folder = ROOT / package.replace(".", "/")
    return name is not None and ((folder / name).is_dir() or (folder / f"{name}.py").exists())


def arrows(package: str) -> dict[tuple[str, str], set[str]]:
    """(importing part, imported part) of `package`, with the modules that import so."""
    found: dict[tuple[str, str], set[str]] = {}
    for path in modules(package.replace(".", "/")):
        module = module_name(path)
        source = part_of(module, package)
        for name in named_modules(path.read_text(), module):
            target = part_of(name, package)
            if source and target != source and is_part(package, target):
                found.setdefault((source, str(target)), set()).add(module)
    return found


def test_every_part_of_reports_has_its_layer() -> None:
    parts = {p.stem for p in (ROOT / "reports").glob("*.py") if p.stem != "__init__"}
    parts |= {p.parent.name for p in (ROOT / "reports").glob("*/__init__.py")}
    assert parts == set(LAYER)


def test_no_arrow_runs_back_up_between_the_parts_of_reports() -> None:
    """Every pair of parts of reports/: an import runs only to a lower layer."""
    upward = {pair: found for pair, found in arrows("reports").items() if LAYER[pair[1]] >= LAYER[pair[0]]}
    assert upward == {}


def packages_of_ours() -> list[str]:
    return sorted(
        module_name(init.parent / "x.py").removesuffix(".x")
        for top in (*OURS, "mbxval")
        for init in (ROOT / top).rglob("__init__.py")
        if "__pycache__" not in init.parts
    )


def cycle_among_parts(package: str) -> tuple[str, ...]:
    """A cycle among the direct subpackages and modules of `package`, or () where there is none."""
    graph: dict[str, set[str]] = {}
    for source, target in arrows(package):
        graph.setdefault(source, set()).add(target)
    try:
        graphlib.TopologicalSorter(graph).prepare()
    except graphlib.CycleError as error:
        return tuple(error.args[1])
    return ()


def test_no_package_of_ours_has_a_cycle_among_its_parts() -> None:
    """Inside every package (the top level's included), its subpackages and modules import each
    other one way."""
    found = {package: cycle_among_parts(package) for package in packages_of_ours()}
    assert {package: cycle for package, cycle in found.items() if cycle} == {}


def test_the_cycle_search_sees_a_cycle(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Two parts that import each other are a cycle; one way is not."""
    import tests.test_layering as rules

    package = tmp_path / "pkg"
    package.mkdir()
    (package / "__init__.py").write_text("")
    (package / "a.py").write_text("from pkg import b\n")
    (package / "b.py").write_text("import os\n")
    monkeypatch.setattr(rules, "ROOT", tmp_path)
    assert cycle_among_parts("pkg") == ()
    (package / "b.py").write_text("from pkg.a import x\n")
    assert set(cycle_among_parts("pkg")) == {"a", "b"}


def face(package: str) -> set[str]:
    """The names the face of `package` offers: its `__init__`'s re-exports under TYPE_CHECKING
    (reports.face)."""
    tree = ast.parse((ROOT / package.replace(".", "/") / "__init__.py").read_text())
    return {
        alias.asname or alias.name
        for node in tree.body
        if isinstance(node, ast.If) and ast.unparse(node.test) == "TYPE_CHECKING"
        for statement in node.body
        if isinstance(statement, ast.ImportFrom)
        for alias in statement.names
    }


def behind_a_face(source: str, module: str) -> list[str]:
    """The imports of `module` that reach behind the face of another package of reports."""
    found = []
    own = part_of(module)
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.ImportFrom) and not node.level:
            named, names = node.module or "", [alias.name for alias in node.names]
        elif isinstance(node, ast.Import):
            named, names = "", [alias.name for alias in node.names]
        else:
            continue
        for name in [f"{named}.{n}" if named else n for n in names]:
            package = part_of(name)
            if package is None or package == own or not (ROOT / "reports" / package / "__init__.py").exists():
                continue
            if name == f"reports.{package}":  # the package itself, read through its face
                continue
            if named != f"reports.{package}" or name.split(".")[-1] not in face(f"reports.{package}"):
                found.append(name)
    return found


def test_other_packages_import_only_a_face() -> None:
    found = {}
    for path in [*modules("reports"), *modules("mbxval")]:
        bad = behind_a_face(path.read_text(), module_name(path))
        if bad:
            found[str(path.relative_to(ROOT))] = bad
    assert found == {}


@pytest.mark.parametrize(
    ("source", "offends"),
    [
        ("from reports.store import ResultsStore\n", []),
        ("from reports import store\n", []),
        (
            "from reports.store.results_store import ResultsStore\n",
            ["reports.store.results_store.ResultsStore"],
        ),
        ("from reports.store import tables\n", ["reports.store.tables"]),
        ("def f():\n    import reports.run.runner\n", ["reports.run.runner"]),
        ("from reports.render.markup import escape\n", []),
    ],
)
def test_the_face_rule_sees_what_reaches_behind(source: str, offends: list[str]) -> None:
    """A name behind the face, a part the face does not offer, a function-level import: offences;
    the face itself, the package as a whole, a module of its own package: not."""
    assert behind_a_face(source, "reports.render.page") == offends


def test_no_part_of_reports_holds_over_a_quarter_of_it() -> None:
    """Each part of reports/ stays a room a reader can walk through: at most about a quarter of the
    lines (30 %)."""
    lines = {part: 0 for part in LAYER}
    for path in modules("reports"):
        part = part_of(module_name(path))
        if part:
            lines[part] += len(path.read_text().splitlines())
    total = sum(lines.values())
    assert {part: n / total for part, n in lines.items() if n > 0.3 * total} == {}
