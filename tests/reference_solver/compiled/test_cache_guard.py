"""compiled.cache_guard.refresh: numba's machine code (*.nbi index and *.nbc data files) under the
package's __pycache__ is dropped when any source changes, kept otherwise; nothing else there is
touched, and a package where no cache can be written is left alone without an error."""

from __future__ import annotations

from pathlib import Path

from reference_solver.compiled.cache_guard import refresh


def package(where: Path, sources: dict[str, str]) -> Path:
    """A package of `sources` (name -> text) with an empty __pycache__."""
    for name, text in sources.items():
        (where / name).write_text(text)
    (where / "__pycache__").mkdir(exist_ok=True)
    return where


def machine_code(where: Path) -> list[Path]:
    """A cached kernel's index and data file, and a bytecode file beside them."""
    cache = where / "__pycache__"
    files = [
        cache / "kernel.run-1.py311.nbi",
        cache / "kernel.run-1.py311.1.nbc",
        cache / "kernel.cpython-311.pyc",
    ]
    for f in files:
        f.write_text("cached")
    return files


def test_unchanged_sources_keep_index_and_data_and_a_change_drops_both_but_not_bytecode(
    tmp_path: Path,
) -> None:
    where = package(tmp_path, {"a.py": "x = 1\n", "b.py": "y = 2\n", "notes.txt": "a\n"})
    refresh(where)
    index, data, bytecode = machine_code(where)
    (where / "notes.txt").write_text("not a source\n")
    refresh(where)
    assert index.exists() and data.exists() and bytecode.exists()
    (where / "b.py").write_text("y = 3\n")
    refresh(where)
    assert not index.exists() and not data.exists() and bytecode.exists()


def test_text_moved_across_two_sources_or_a_renamed_source_is_a_change(tmp_path: Path) -> None:
    """The joined text of a.py and b.py is the same before and after the move; the guard must still
    see that the sources changed."""
    where = package(tmp_path, {"a.py": "x = 1\ny = 2\n", "b.py": "z = 3\n"})
    refresh(where)
    index = machine_code(where)[0]
    (where / "a.py").write_text("x = 1\n")
    (where / "b.py").write_text("y = 2\nz = 3\n")
    refresh(where)
    assert not index.exists()
    index = machine_code(where)[0]
    (where / "b.py").rename(where / "c.py")
    refresh(where)
    assert not index.exists()


def test_a_package_whose_cache_cannot_be_made_is_left_alone(tmp_path: Path) -> None:
    """__pycache__ a plain file (so no directory can be made there, as in a read-only checkout)."""
    (tmp_path / "a.py").write_text("x = 1\n")
    (tmp_path / "__pycache__").write_text("not a directory")
    refresh(tmp_path)
    assert (tmp_path / "__pycache__").read_text() == "not a directory"


KERNEL = """
from numba import njit

from proj.profile import radius

_radius = njit(cache=True, inline="always")(radius)


@njit(cache=True)
def run(x):
    return _radius(x) + 1.0
"""

CALL = """
import sys
from pathlib import Path

root = Path(sys.argv[1])
if sys.argv[2] == "guarded":
    from reference_solver.compiled.cache_guard import refresh

    refresh(root / "proj" / "fast")
sys.path.insert(0, str(root))
from proj.fast.kernel import run

print(run(3.0))
"""


def test_an_edit_to_an_inlined_function_in_another_package_recompiles_the_kernel(tmp_path: Path) -> None:
    """A kernel in proj/fast inlines proj.profile.radius, as compiled/evaluate.py inlines the cam
    profiles of scenarios/: numba's own cache, keyed on the kernel's file, keeps the old formula
    after radius changes; the guard drops it and the kernel compiles the new one."""
    import subprocess
    import sys

    (tmp_path / "proj" / "fast").mkdir(parents=True)
    (tmp_path / "proj" / "__init__.py").write_text("")
    (tmp_path / "proj" / "fast" / "__init__.py").write_text("")
    (tmp_path / "proj" / "fast" / "kernel.py").write_text(KERNEL)
    profile = tmp_path / "proj" / "profile.py"
    profile.write_text("def radius(x):\n    return 2.0 * x\n")

    def call(mode: str) -> float:
        done = subprocess.run(
            [sys.executable, "-c", CALL, str(tmp_path), mode], capture_output=True, text=True, check=True
        )
        return float(done.stdout)

    assert call("guarded") == 7.0
    profile.write_text("def radius(x):\n    return 3.0 * x\n")
    assert call("unguarded") == 7.0  # numba alone: the stale machine code
    assert call("guarded") == 10.0


def test_the_compiled_path_s_sources_include_the_project_modules_its_kernels_inline() -> None:
    import reference_solver.compiled as compiled
    from reference_solver.compiled.cache_guard import compiled_sources

    package = Path(compiled.__file__).parent
    names = {source.relative_to(package.parents[1]).as_posix() for source in compiled_sources(package)}
    assert {"scenarios/cam_profiles.py", "reference_solver/limits.py", "scenarios/motions.py"} <= names
    assert {p.relative_to(package.parents[1]).as_posix() for p in package.glob("*.py")} <= names
