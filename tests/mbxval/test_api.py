"""The Python API used as a notebook uses it: import mbxval, solve, load, run, compare, read back."""

from __future__ import annotations

import subprocess
import sys
from importlib import metadata
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import mbxval
from reports.run.engine_facts import engine_packages
from scenarios.closed_form import exact

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def test_solve_with_a_parameter_matches_the_closed_form() -> None:
    frame = mbxval.solve("slider_crank", steps=50, offset=0.05, crank_length=0.15)
    scenario = mbxval.load_scenario("slider_crank", steps=50, offset=0.05, crank_length=0.15)
    truth = exact(scenario).to_frame()  # an independent derivation, not the solver under test
    assert list(frame.columns[:4]) == ["t", "crank.x", "crank.y", "crank.theta"]
    assert len(frame) == 51
    scale = truth.abs().max().clip(lower=1.0)  # per column: lengths, rates, accelerations apart
    assert ((frame[truth.columns] - truth).abs().max() <= 1e-9 * scale).all()
    assert frame["slider.y"].abs().max() > 0.04  # the offset was applied, not the default 0


def test_solve_takes_the_grid_and_an_engine_setting() -> None:
    frame = mbxval.solve("four_bar", engine="reference", t_end=0.05, steps=10, settings={"tolerance": 1e-10})
    np.testing.assert_allclose(frame["t"], np.linspace(0.0, 0.05, 11))


def test_bad_arguments_raise_value_errors_with_the_command_lines_message() -> None:
    with pytest.raises(mbxval.ArgumentError, match="unknown engine 'nope'"):
        mbxval.solve("four_bar", engine="nope")
    with pytest.raises(mbxval.ScenarioError, match="unknown parameter 'offsett'"):
        mbxval.solve("slider_crank", offsett=0.1)
    with pytest.raises(ValueError, match="steps"):
        mbxval.solve("four_bar", steps=0)
    with pytest.raises(mbxval.ArgumentError, match="built Scenario"):
        mbxval.solve(mbxval.load_scenario("four_bar"), offset=1.0)


def test_load_a_scenario_file_with_a_value_set() -> None:
    scenario = mbxval.load_scenario(EXAMPLES / "slider_crank.toml", t_end=0.5, steps=25)
    assert isinstance(scenario, mbxval.Scenario)
    assert (scenario.t_end, scenario.steps) == (0.5, 25)
    assert scenario.times()[-1] == 0.5


def test_a_narrow_run_into_a_directory_and_read_back(tmp_path: Path) -> None:
    out = tmp_path / "results"
    frame = mbxval.run("four_bar", "reference", suite="quick", out=out, steps=40, report=False, repeats=1)
    assert list(frame["scenario"]) == ["four_bar[steps=40]"]
    row = frame.iloc[0]
    assert (row["engine"], row["status"], row["truth"]) == ("reference", "ok", "closed form")
    assert row["error_position"] < 1e-9
    again = mbxval.read_results(out)
    pd.testing.assert_frame_equal(again, frame)
    assert again.attrs["results"] == str(out) and "git_revision" in again.attrs["meta"]


def test_run_refuses_a_parameter_a_scenario_lacks_before_running(tmp_path: Path) -> None:
    with pytest.raises(mbxval.ScenarioError, match="four_bar: unknown parameter 'offset'"):
        mbxval.run(["slider_crank", "four_bar"], "reference", out=tmp_path / "r", parameters={"offset": 0.01})
    assert not (tmp_path / "r").exists()


def test_compare_scores_a_trajectory_frame_and_sees_an_error() -> None:
    frame = mbxval.solve("slider_crank", steps=40)
    row = mbxval.compare("slider_crank", frame, label="mine", steps=40).iloc[0]
    assert (row["engine"], row["truth"]) == ("mine", "closed form")
    assert row["error_position"] < 1e-10
    moved = frame.copy()
    moved["slider.x"] += 1e-3 * mbxval.load_scenario("slider_crank").characteristic_length
    error = mbxval.compare("slider_crank", moved, steps=40).iloc[0]["error_position"]
    assert 0.5e-3 < error < 2e-3  # the displacement, in lengths of the scenario's scale


def test_compare_reads_a_csv_and_names_what_is_wrong(tmp_path: Path) -> None:
    path = tmp_path / "tool.csv"
    mbxval.solve("four_bar", steps=30).to_csv(path, index=False)
    assert mbxval.compare("four_bar", path, steps=30).iloc[0]["error_position"] < 1e-9
    with pytest.raises(mbxval.ArgumentError, match="has 31 time rows"):
        mbxval.compare("four_bar", path)


def test_version_from_the_package_metadata_and_the_command_line() -> None:
    assert mbxval.__version__ == metadata.version("mbxval")
    for flag in ("--version", "-V"):
        command = [sys.executable, "-m", "mbxval", flag]
        done = subprocess.run(command, capture_output=True, text=True, check=False)
        assert done.returncode == 0, done.stderr
        lines = done.stdout.splitlines()
        assert lines[0] == f"mbxval {mbxval.__version__}"
        engines = {line.split()[0]: line.split()[1] for line in lines[1:]}
        assert {e: engines[e] for e in engine_packages()} == {
            e: metadata.version(e) for e in engine_packages()
        }
