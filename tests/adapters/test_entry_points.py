"""An engine from another package: the minimal engine of docs/adding-an-engine.md, built as a
throwaway package, installed with pip into a folder of its own, found through the `mbxval.engines`
entry-point group, and run on the default suite by the command line."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest

ROOT = Path(__file__).resolve().parents[2]
PYPROJECT = """[build-system]
requires = ["setuptools>=61"]
build-backend = "setuptools.build_meta"

[project]
name = "my-engine"
version = "0.1"

[tool.setuptools]
packages = ["my_engine"]

"""


def documented_blocks() -> tuple[str, str]:
    text = (ROOT / "docs" / "adding-an-engine.md").read_text()
    section = text[text.index("## Your own solver as an engine") :]
    code = re.search(r"```python\n(# my_engine/__init__\.py\n.*?)```", section, flags=re.S)
    toml = re.search(
        r"```toml\n(\[project\.entry-points\.\"mbxval\.engines\"\]\n.*?)```", section, flags=re.S
    )
    assert code and toml, "the documented minimal engine and its entry point"
    return code.group(1), toml.group(1)


@pytest.fixture(scope="module")
def site(tmp_path_factory: pytest.TempPathFactory) -> Path:
    code, entry = documented_blocks()
    assert len(code.splitlines()) < 60
    package = tmp_path_factory.mktemp("my-engine")
    (package / "my_engine").mkdir()
    (package / "my_engine" / "__init__.py").write_text(code)
    (package / "pyproject.toml").write_text(PYPROJECT + entry)
    target = tmp_path_factory.mktemp("site")
    install = [
        sys.executable,
        "-m",
        "pip",
        "install",
        "-q",
        "--no-deps",
        "--no-build-isolation",  # the test environment's own setuptools: no package index needed
        "--target",
        str(target),
        str(package),
    ]
    done = subprocess.run(install, capture_output=True, text=True, check=False)
    assert done.returncode == 0, done.stderr
    return target


def mbxval(site: Path, *args: str) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(site), str(ROOT)])}
    command = [sys.executable, "-m", "reports.cli", *args]
    return subprocess.run(command, capture_output=True, text=True, env=env, cwd=ROOT, check=False)


def test_the_installed_engine_is_listed_and_solves(site: Path, tmp_path: Path) -> None:
    listed = mbxval(site, "list")
    assert listed.returncode == 0, listed.stderr
    header = next(line for line in listed.stdout.splitlines() if line.startswith("scenario"))
    assert header.split()[-1] == "closed_form"
    solved = mbxval(site, "solve", "four_bar", "--engine", "closed_form", "--out", str(tmp_path / "fb.csv"))
    assert solved.returncode == 0, solved.stderr
    assert pd.read_csv(tmp_path / "fb.csv").shape == (201, 1 + 9 * 3)
    bad = mbxval(site, "solve", "four_bar", "--engine", "closed_form", "--setting", "digits=40")
    assert bad.returncode == 2 and bad.stderr.strip().endswith(
        "option digits must be an int in [1, 17], got 40"
    )


def test_the_default_suite_runs_on_the_installed_engine(site: Path, tmp_path: Path) -> None:
    done = mbxval(site, "run", "--engine", "closed_form", "--out", str(tmp_path / "run"))
    assert done.returncode == 0, done.stderr
    rows = pd.read_parquet(tmp_path / "run" / "results.parquet")
    assert set(rows.engine) == {"closed_form"}
    assert set(rows.status) == {"ok", "unsupported"}
    assert set(rows[rows.status == "unsupported"].scenario) == {
        "cam_knife_edge/spline",
        "cam_roller/spline",
        "cam_flat_face/spline",
    }
    ok = rows[rows.status == "ok"]
    # rounding to d significant digits costs half a unit in the d-th digit of values that reach a few
    # characteristic lengths: between 1e-(d+2) and 1e-(d-2) of it
    for digits in (4, 8):
        error = ok[ok.setting == f"exact digits={digits}"].error
        assert (
            len(error) == 14
            and (error > 10.0 ** -(digits + 2)).all()
            and (error < 10.0 ** -(digits - 2)).all()
        )
    assert (ok[ok.setting == "exact digits=17"].error < 1e-9).all()
    assert json.loads((tmp_path / "run" / "results.json").read_text())["engines"]["closed_form"] == "0.1"
