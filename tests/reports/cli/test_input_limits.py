"""Declared limits on what the command line takes, each refused in one bounded line, exit 2, before
anything is planned or started: the end time, the workers, a cluster's port, a sweep's size, a file's
sections and arrays; a message quoting a huge value stays one line of bounded length."""

from __future__ import annotations

import time
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from reports.cli.main import main
from reports.cli.suite_commands import MAX_WORKERS
from reports.run.stop import MAX_MESSAGE
from scenarios import ScenarioError
from scenarios.files.reader import MAX_NUMBERS, MAX_TABLES, Reader, parse_scenario
from scenarios.files.schema import Key

HEAD = 'format = 1\nname = "f"\nt_end = 1.0\nsteps = 10\ncharacteristic_length = 1.0\n'


def refused(capsys: pytest.CaptureFixture[str], argv: list[str], words: str) -> str:
    started = time.monotonic()
    assert main(argv) == 2
    assert time.monotonic() - started < 20
    err = capsys.readouterr().err
    assert err.startswith("mbxval: error: ") and err.count("\n") == 1, err[:300]
    assert words in err, err[:300]
    return err


@pytest.mark.parametrize("t_end", ["5e-324", "1e-12", "2e6"])
def test_an_end_time_outside_its_range(capsys, t_end: str) -> None:
    refused(capsys, ["solve", "slider_crank", "--t-end", t_end], "--t-end must be in [1e-09, 1e+06] s")


def test_more_workers_than_the_machine_can_hold(capsys, tmp_path: Path) -> None:
    argv = ["run", "--scenario", "four_bar", "--engine", "reference", "--out", str(tmp_path / "o")]
    refused(capsys, [*argv, "--workers", str(MAX_WORKERS + 1)], f"--workers must be in [1, {MAX_WORKERS}]")
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("address", ["tcp://127.0.0.1:99999", "tcp://127.0.0.1:0", "127.0.0.1:8786"])
def test_a_cluster_address_out_of_range(capsys, tmp_path: Path, address: str) -> None:
    argv = ["run", "--scenario", "four_bar", "--engine", "reference", "--out", str(tmp_path / "o")]
    refused(capsys, [*argv, "--cluster", address], "port in [1, 65535]")
    assert not (tmp_path / "o").exists()


def test_a_sweep_too_large_is_refused_before_its_points_are_made(capsys, tmp_path: Path) -> None:
    argv = ["run", "--scenario", "four_bar", "--engine", "reference", "--out", str(tmp_path / "o")]
    refused(capsys, [*argv, "--sweep", "omega=log:1:1e6:100000"], "N must be in [1, 10000]")
    grid = ["--sweep", "omega=lin:1:2:200", "--sweep", "crank_length=lin:0.01:0.04:100"]
    refused(capsys, [*argv, *grid], "20000 points")


def test_a_file_without_bodies(capsys, tmp_path: Path) -> None:
    path = tmp_path / "empty.toml"
    path.write_text(HEAD + "bodies = []\n")
    refused(capsys, ["solve", str(path)], "bodies: 0 tables; a scenario file holds 1 to")


def test_a_file_with_more_bodies_than_declared(capsys, tmp_path: Path) -> None:
    bodies = "".join(f'[[bodies]]\nname = "b{k}"\n\n' for k in range(MAX_TABLES["bodies"] + 1))
    path = tmp_path / "many.toml"
    path.write_text(HEAD + bodies)
    refused(capsys, ["solve", str(path)], f"a scenario file holds 1 to {MAX_TABLES['bodies']} [[bodies]]")


def test_an_array_longer_than_declared() -> None:
    reader = Reader("f.toml", Path("."))
    assert len(reader.numbers([0.05] * MAX_NUMBERS, Key("numbers"), "table")) == MAX_NUMBERS
    with pytest.raises(ScenarioError, match=f"more than the {MAX_NUMBERS} an array may hold"):
        reader.numbers([0.05] * (MAX_NUMBERS + 1), Key("numbers"), "table")


def test_a_huge_quoted_value_stays_one_bounded_line(capsys) -> None:
    err = refused(capsys, ["solve", "slider_crank", "--set", "offset=" + "x" * 1_000_000], "offset")
    assert len(err) <= MAX_MESSAGE + len("mbxval: error: \n")


@pytest.mark.slow  # Dask gives up on the address after its 10 s connect timeout
def test_an_unreachable_cluster_leaves_no_folder_behind(capsys, tmp_path: Path) -> None:
    out = tmp_path / "o"
    argv = ["run", "--scenario", "four_bar", "--engine", "reference", "--out", str(out), "--quiet"]
    started = time.monotonic()
    assert main([*argv, "--cluster", "tcp://127.0.0.1:9"]) == 2
    assert time.monotonic() - started < 60
    assert capsys.readouterr().err.count("\n") == 1
    assert not out.exists()


def test_a_run_that_would_keep_too_much_is_refused_before_it_starts(capsys, tmp_path: Path) -> None:
    """Each grid passes alone (192 MiB a trajectory, under a minute's work), but the run keeps 5
    per scenario of 5 scenarios: 4.4 GiB."""
    out = tmp_path / "o"
    names = ["slider_crank", "four_bar", "slider_crank/offset", "four_bar/crossed", "rack_pinion"]
    argv = ["run", *(f"--scenario={name}" for name in names), "--out", str(out)]
    refused(capsys, [*argv, "--steps", "900000"], "more than 4 GiB")
    assert not out.exists()


@settings(max_examples=25, deadline=None, derandomize=True)
@given(bodies=st.integers(0, MAX_TABLES["bodies"] + 50), numbers=st.integers(0, 12))
def test_drawn_sizes_are_read_or_refused_in_one_line(bodies: int, numbers: int) -> None:
    """Any number of bodies (each with a guess of `numbers` values) parses within the limits, or is
    refused naming the limit it breaks; never anything else."""
    tables = "".join(
        f'[[bodies]]\nname = "b{k}"\nguess = [{", ".join(["0.0"] * numbers)}]\n\n' for k in range(bodies)
    )
    try:
        scenario = parse_scenario(HEAD + (tables or "bodies = []\n"), "drawn.toml")
    except ScenarioError as error:
        message = str(error)
        assert "\n" not in message
        if not 1 <= bodies <= MAX_TABLES["bodies"]:
            assert "a scenario file holds 1 to" in message
        else:
            assert numbers != 3 and "guess" in message  # a guess is a pose of 3 numbers
    else:
        assert 1 <= bodies <= MAX_TABLES["bodies"] and numbers == 3 and len(scenario.bodies) == bodies
