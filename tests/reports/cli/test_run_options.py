"""`run` takes what `solve` takes (--set, --t-end, --steps on every scenario), its counts add up (the
bar counts runs; the last line gives this run's rows apart from the store's total), and `list`
gives one name per mode and the dynamic families in its table."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from reports.cli.main import main
from reports.store.results_store import read_results, read_trajectories
from scenarios import all_families

NARROW = ["--suite", "quick", "--engine", "reference", "--repeats", "1", "--warmup", "0"]


def test_set_t_end_and_steps_apply_to_every_scenario(tmp_path: Path, capsys) -> None:
    argv = ["run", "--out", str(tmp_path), *NARROW, "--scenario", "four_bar", "--scenario", "slider_crank"]
    assert main([*argv, "--set", "omega=20", "--t-end", "0.25", "--steps", "25"]) == 0
    captured = capsys.readouterr()
    frame, _ = read_results(tmp_path)
    names = sorted(frame["scenario"])
    assert names == ["four_bar[omega=20,t_end=0.25,steps=25]", "slider_crank[omega=20,t_end=0.25,steps=25]"]
    assert set(frame["status"]) == {"ok"} and set(frame["truth"]) == {"closed form"}
    for key, trajectory in read_trajectories(tmp_path).items():
        np.testing.assert_allclose(trajectory.times, np.linspace(0.0, 0.25, 26), err_msg=str(key))
    # the bar counts the 2 runs (the truths are not runs); the last line says what this run made
    assert "2/2" in captured.err and "4/4" not in captured.err and "3/3" not in captured.err
    assert captured.out.startswith(f"2 runs (ok 2); {tmp_path} holds 2 rows; report: ")


def test_the_last_line_counts_this_run_apart_from_the_store(tmp_path: Path, capsys) -> None:
    base = ["run", "--out", str(tmp_path), *NARROW, "--quiet", "--steps", "20"]
    assert main([*base, "--scenario", "four_bar"]) == 0
    assert main([*base, "--scenario", "four_bar", "--scenario", "spur_gears"]) == 0
    last = capsys.readouterr().out.splitlines()[-1]
    assert last.startswith(f"1 runs (ok 1); {tmp_path} holds 2 rows")


def test_a_parameter_one_scenario_lacks_is_one_error_line(tmp_path: Path, capsys) -> None:
    argv = ["run", "--out", str(tmp_path / "out"), *NARROW, "--scenario", "slider_crank"]
    assert main([*argv, "--scenario", "four_bar", "--set", "offset=0.05"]) == 2
    error = capsys.readouterr().err
    assert error.startswith("mbxval: error: four_bar: unknown parameter 'offset'") and error.count("\n") == 1
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize(("option", "value"), [("--t-end", "-1"), ("--steps", "0"), ("--set", "omega")])
def test_a_bad_grid_or_pair_is_one_error_line(tmp_path: Path, capsys, option: str, value: str) -> None:
    argv = ["run", "--out", str(tmp_path / "out"), *NARROW, "--scenario", "four_bar", option, value]
    assert main(argv) == 2
    error = capsys.readouterr().err
    assert error.startswith("mbxval: error: ") and error.count("\n") == 1
    assert not (tmp_path / "out").exists()


def test_list_gives_one_name_per_mode_and_every_family_it_lists(capsys) -> None:
    assert main(["list"]) == 0
    out = capsys.readouterr().out
    table, modes = out.split("\nmodes:")[0], out.split("\nmodes:")[1].split("\n\n")[0]  # to its blank line
    listed = [line.split(":")[0].split() for line in modes.splitlines()[1:] if line.strip()]
    assert len(listed) == len({tuple(pair) for pair in listed})
    names = {mode for _, mode in listed}
    assert {"kinematic", "dynamic"} <= names and not {"kinematics", "dynamics"} & names
    rows = {line.split()[0].split("/")[0] for line in table.splitlines()[2:] if line.strip()}
    assert set(all_families()) <= rows  # the dynamic families whose parameters it lists too


def test_a_mode_name_the_engine_does_not_have_is_one_error_line_naming_its_modes(capsys) -> None:
    argv = ["solve", "four_bar", "--engine", "pinocchio", "--steps", "20"]
    assert main([*argv, "--mode", "kinematics"]) == 2
    captured = capsys.readouterr()
    assert captured.out == "" and captured.err.count("\n") == 1
    assert captured.err.startswith("mbxval: error: pinocchio: unknown mode 'kinematics'")
    assert "known: kinematic, dynamic, baumgarte, euler" in captured.err
