"""Every dynamic built-in family exported with `mbxval export NAME --format toml` and read back is
the same scenario, and the native forward dynamics (its default setting) gives bit-identical
trajectories from the file and from the family. The first cases shorten the horizon (the file's
content does not depend on it); the second export each scenario as the catalogue has it and, the
scenarios being equal, simulate the first points of its own grid (the step the default setting
takes from the whole scenario)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import adapters
import scenarios
from reports.cli.main import main
from scenarios import Scenario
from scenarios.files import read_scenario
from scenarios.files.writer import read_back

DYNAMIC = [n for n in scenarios.catalogue(include_dynamic=True) if scenarios.build(n).analysis == "dynamic"]
SHORT = {"stiff_spring": ("t_end=0.004", "dt=0.001")}
"""--set values that make each family's run short (the default: a few steps of 5 ms)."""


def _short(name: str) -> tuple[str, ...]:
    return SHORT.get(name.split("/")[0], ("t_end=0.01", "steps=2"))


def _assert_same_dynamics(family: Scenario, from_file: Scenario, points: int | None = None) -> None:
    native = adapters.load("reference")
    setting = native.default_setting(family)
    assert native.default_setting(from_file) == setting
    times = np.asarray(family.times())[:points]
    a, b = native.run(family, setting, times), native.run(from_file, setting, times)
    assert a.status == b.status == "ok", (a.message, b.message)
    assert a.trajectory is not None and b.trajectory is not None
    assert a.trajectory.bodies == b.trajectory.bodies
    for level in ("position", "velocity", "acceleration"):
        assert np.array_equal(a.trajectory.level(level), b.trajectory.level(level)), level
    assert a.trajectory.extras.keys() == b.trajectory.extras.keys()
    for key, values in a.trajectory.extras.items():
        assert np.array_equal(b.trajectory.extras[key], values), key


def _exported(tmp_path: Path, capsys: pytest.CaptureFixture[str], name: str, *sets: str) -> Scenario:
    target = tmp_path / "exported.toml"
    argv = ["export", name, "--format", "toml", "--out", str(target)]
    for value in sets:
        argv += ["--set", value]
    assert main(argv) == 0, capsys.readouterr().err
    return read_scenario(target)


def test_there_are_dynamic_families_with_every_kind_of_load() -> None:
    """The round trip below covers gravity, every force kind the families use, and body rates."""
    built = [scenarios.build(n) for n in DYNAMIC]
    kinds = {type(f).__name__ for s in built for f in s.forces}
    assert {"AppliedTorque", "SpringDamper"} <= kinds
    assert any(s.gravity != (0.0, 0.0) for s in built)
    assert any(b.rate != (0.0, 0.0, 0.0) for s in built for b in s.bodies)
    assert any(s.angle_outputs for s in built)


@pytest.mark.parametrize(
    "name", [pytest.param(n, marks=[pytest.mark.slow] if n == "n_four_bar/spec" else []) for n in DYNAMIC]
)  # the spec variant's 81 bodies take most of a minute even over two steps
def test_dynamic_family_exported_reads_back_equal_and_simulates_bit_identically(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], name: str
) -> None:
    sets = _short(name)
    family = scenarios.build(name, overrides=dict(s.split("=") for s in sets))
    from_file = _exported(tmp_path, capsys, name, *sets)
    assert from_file == read_back(family)
    _assert_same_dynamics(family, from_file)


@pytest.mark.parametrize("name", [n for n in DYNAMIC if n != "n_four_bar/spec"])
def test_dynamic_family_at_its_own_horizon_simulates_bit_identically(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], name: str
) -> None:
    family, from_file = scenarios.build(name), _exported(tmp_path, capsys, name)
    assert from_file == read_back(family)
    _assert_same_dynamics(family, from_file, points=4)
