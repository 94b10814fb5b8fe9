"""`mbxval bench mutation` on a small module: every mutant of the level errors is killed by their
tests or explained as equivalent (the habit kept cheap: about 20 s on one worker)."""

from __future__ import annotations

import importlib
import json
import re
from pathlib import Path

import pytest

from benchmarks.mutation import (
    EXPLAINED,
    KERNEL_MODULES,
    MODULES,
    ROOT,
    _environment,
    _scratch_copy,
    run,
)
from benchmarks.mutation_results import EXPLAINED_DIR

MUTANT = re.compile(r"(?P<module>.*?)\.x(?:_(?P<function>.*)|ǁ(?P<cls>.*)ǁ(?P<method>.*))__mutmut_\d+$")


@pytest.mark.slow
def test_every_mutant_of_the_level_errors_is_killed_or_explained() -> None:
    outcome = run("reports/scoring/level_error.py", niceness=0)
    assert outcome.total > 50 and outcome.timeout == 0 and outcome.other == 0
    assert outcome.unexplained == ()
    assert outcome.killed == outcome.total - len(outcome.survivors)


def test_an_unknown_module_is_refused_by_name() -> None:
    with pytest.raises(ValueError, match=r"no mutation setup for reports/nowhere\.py"):
        run("reports/nowhere.py")
    assert all(tests for tests in MODULES.values()) and all(EXPLAINED.values())


def test_a_kernel_module_is_mutated_as_the_python_numba_compiles(tmp_path: Path) -> None:
    """Its copy loses only the `@njit(...)` lines, one per kernel, and the run has numba off (under
    which njit returns the function itself); any other module keeps numba on, its cache in the copy."""
    module = "reference_solver/compiled/band.py"
    _scratch_copy(module, tmp_path)
    original = (ROOT / module).read_text().splitlines(keepends=True)
    stripped = (tmp_path / module).read_text().splitlines(keepends=True)
    kernels = [line for line in original if line.startswith("@njit(")]
    assert len(kernels) == 10 and [line for line in original if line not in kernels] == stripped
    assert (tmp_path / "reference_solver/compiled/loop.py").read_text() == (
        ROOT / "reference_solver/compiled/loop.py"
    ).read_text()
    assert _environment(module, tmp_path)["NUMBA_DISABLE_JIT"] == "1"
    other = _environment("reference_solver/compiled/rows.py", tmp_path)
    assert "NUMBA_DISABLE_JIT" not in other
    assert Path(other["NUMBA_CACHE_DIR"]).parent == tmp_path
    assert set(MODULES) >= KERNEL_MODULES


def test_every_explained_survivor_names_a_function_its_module_still_has() -> None:
    """Each file holds its own module's survivors, each with a reason, and each mutant's function
    (or class and method) still exists: a rename leaves no explanation behind for code that is gone."""
    files = sorted(EXPLAINED_DIR.glob("*.json"))
    assert len(files) >= 29
    for path in files:
        module = path.stem
        assert f"{module.replace('.', '/')}.py" in MODULES, path.name
        source = importlib.import_module(module)
        for name, reason in json.loads(path.read_text()).items():
            match = MUTANT.match(name)
            assert match is not None and match["module"] == module, name
            assert reason.strip(), name
            if match["function"] is not None:
                assert hasattr(source, match["function"]), name
            else:
                assert hasattr(getattr(source, match["cls"], None), match["method"]), name
    assert sum(len(json.loads(path.read_text())) for path in files) == len(EXPLAINED)
