"""Each command imports what it uses (issue #40): `mbxval --help` and `--version` import no pandas,
matplotlib, numba or scipy.interpolate; a kinematic solve of a few points none of them, nor
scipy.integrate or scipy.sparse (the plain path pays below reference_solver.compiled.PAYS_FROM), and a
long one only the compiled path's numba. Checked by the modules a fresh interpreter holds after the
command, never by time."""

from __future__ import annotations

import io
import json
import subprocess
import sys

import numpy as np
import pandas as pd

from scenarios import Trajectory

HEAVY = ("pandas", "matplotlib", "numba", "scipy.interpolate", "tqdm", "pyarrow", "dask", "distributed")
SOLVER_ONLY = ("numba", "scipy.integrate", "scipy.sparse", "scipy.optimize")
"""What the native solver imports for one path or the other: forward dynamics, the compiled band."""

PROBE = """
import contextlib, io, json, sys
from reports.entry import main
with contextlib.redirect_stdout(io.StringIO()), contextlib.suppress(SystemExit):
    main(json.loads(sys.argv[1]))
print(json.dumps(sorted(name for name in json.loads(sys.argv[2]) if name in sys.modules)))
"""


def imported(argv: list[str], watched: tuple[str, ...] = HEAVY) -> set[str]:
    """Which of `watched` a fresh interpreter has imported after running `mbxval` with `argv`."""
    done = subprocess.run(
        [sys.executable, "-c", PROBE, json.dumps(argv), json.dumps(watched)],
        capture_output=True,
        text=True,
        timeout=300,
        check=True,
    )
    return set(json.loads(done.stdout.strip().splitlines()[-1]))


def test_help_imports_none_of_them() -> None:
    assert imported(["--help"], HEAVY + SOLVER_ONLY + ("scipy.linalg", "reference_solver")) == set()


def test_a_commands_help_imports_none_of_them() -> None:
    assert imported(["run", "--help"]) == set()


ENGINE_MODULES = """
import json
from importlib.metadata import packages_distributions
import adapters
dists = set()
for name in adapters.names():
    try:
        dists.update(adapters.load(name).packages)
    except adapters.EngineUnavailable:  # not installed: --version loads it no more than this does
        pass
mine = [m for m, of in packages_distributions().items() if dists & set(of) and m.isidentifier()]
print(json.dumps(sorted(mine)))
"""

OWN = """
import importlib, json, sys
for module in json.loads(sys.argv[1]):
    try:
        importlib.import_module(module)
    except Exception:
        pass
print(json.dumps(sorted(name for name in json.loads(sys.argv[2]) if name in sys.modules)))
"""


def engines_own() -> set[str]:
    """Which of HEAVY the engines' own libraries import, in a fresh interpreter that imports only
    them (the distributions each adapter declares in `packages`): an engine's library may bring some."""
    modules = (
        subprocess.run(
            [sys.executable, "-c", ENGINE_MODULES], capture_output=True, text=True, timeout=300, check=True
        )
        .stdout.strip()
        .splitlines()[-1]
    )
    done = subprocess.run(
        [sys.executable, "-c", OWN, modules, json.dumps(HEAVY)],
        capture_output=True,
        text=True,
        timeout=300,
        check=True,
    )
    return set(json.loads(done.stdout.strip().splitlines()[-1]))


def test_version_imports_none_of_them_beyond_what_the_engines_themselves_import() -> None:
    """`--version` loads every engine to ask its version: it may hold what an engine's own library
    imports, and nothing of HEAVY more."""
    assert imported(["--version"]) <= engines_own()
    assert engines_own() <= {"matplotlib"}  # an engine library that pulls in more is worth knowing


def test_a_kinematic_solve_of_two_points_imports_none_of_them() -> None:
    assert imported(["solve", "four_bar", "--steps", "1"], HEAVY + SOLVER_ONLY) == set()


def test_a_long_kinematic_solve_imports_the_compiled_paths_numba_and_no_integrator() -> None:
    # 4,001 points of 9 coordinates: above PAYS_FROM, so the compiled path runs (and the probe
    # sees numba: the check can fail)
    found = imported(["solve", "four_bar", "--steps", "4000"], HEAVY + SOLVER_ONLY)
    assert found == {"numba", "scipy.sparse"}


def test_the_probe_sees_an_import() -> None:
    # the check can fail: a command that reads a store imports pandas, and the probe says so
    assert "pandas" in imported(["report", "/nonexistent/mbxval-store"])


def test_the_csv_a_solve_writes_is_the_one_pandas_writes() -> None:
    times = np.linspace(0.0, 1.0, 5)
    values = np.array([[[0.1, -0.0, 1 / 3]], [[np.nan, np.inf, -np.inf]], [[1e-300, 3e20, 2.0]]] * 2)[:5]
    extras = {"odd": np.array([np.nan, 0.25, -7.5, 1e17, 5.0])}
    trajectory = Trajectory(times, ("crank",), extras=extras, position=values, velocity=2 * values)
    written, expected = io.StringIO(), io.StringIO()
    trajectory.write_csv(written)
    trajectory.to_frame().to_csv(expected, index=False, float_format="%.17g")
    assert written.getvalue() == expected.getvalue()
    back = Trajectory.from_frame(pd.read_csv(io.StringIO(written.getvalue())))
    np.testing.assert_array_equal(back.position, trajectory.position)  # type: ignore[arg-type]
