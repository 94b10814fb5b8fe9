"""Every public function of the Python API refuses an argument of the wrong type where it enters:
one ArgumentError (a ValueError) on one line naming the argument and what it must be, never a raw
TypeError, AttributeError or OSError from deep inside, and a bool is no number."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import pytest

import mbxval
from scenarios.limits import MAX_LABEL_LENGTH

FRAME = pd.DataFrame({"t": [0.0, 1.0]})
"""A trajectory frame for the calls refused before it is read."""


def _run(**arguments: Any) -> Callable[[], object]:
    """mbxval.run of one cheap scenario with `arguments` replaced (its out a path never written)."""
    given = {"scenarios": "four_bar", "engines": "reference", "suite": "quick", "report": False}
    given.update(arguments)
    return lambda: mbxval.run(**given)


# (the call, the start of the message it must raise)
CASES: dict[str, tuple[Callable[[], object], str]] = {
    "steps a float": (
        lambda: mbxval.solve("four_bar", steps=10.5),
        "steps must be an int or None, got float 10.5",
    ),
    "steps a bool": (
        lambda: mbxval.solve("four_bar", steps=True),
        "steps must be an int or None, got bool True",
    ),
    "steps a numpy float": (
        lambda: mbxval.solve("four_bar", steps=np.float64(10.0)),
        "steps must be an int or None, got float64",
    ),
    "steps a text": (
        lambda: mbxval.solve("four_bar", steps="10"),
        "steps must be an int or None, got str '10'",
    ),
    "t_end a text": (
        lambda: mbxval.solve("four_bar", t_end="abc"),
        "t_end must be a number (float or int) or None",
    ),
    "t_end a bool": (lambda: mbxval.solve("four_bar", t_end=True), "t_end must be a number"),
    "t_end complex": (lambda: mbxval.solve("four_bar", t_end=1j), "t_end must be a number"),
    "settings a text": (
        lambda: mbxval.solve("four_bar", settings="tolerance=1e-3"),
        "settings must be a mapping of names to values (a dict) or None, got str 'tolerance=1e-3'",
    ),
    "settings a list": (
        lambda: mbxval.solve("four_bar", settings=["tolerance=1e-3"]),
        "settings must be a mapping",
    ),
    "a setting None": (
        lambda: mbxval.solve("four_bar", settings={"tolerance": None}),
        "settings['tolerance'] must be a number or a str, got NoneType None",
    ),
    "a setting a bool": (
        lambda: mbxval.solve("four_bar", settings={"tolerance": True}),
        "settings['tolerance'] must be a number or a str, got bool True",
    ),
    "a setting's key with '='": (
        lambda: mbxval.solve("four_bar", settings={"a=b": 1}),
        "a key of settings must be a non-empty str without '='",
    ),
    "a setting's key a number": (
        lambda: mbxval.solve("four_bar", settings={5: 1}),
        "a key of settings must be a non-empty str",
    ),
    "engine a list": (
        lambda: mbxval.solve("four_bar", engine=["reference"]),
        "engine must be a str, got list",
    ),
    "engine with a newline": (
        lambda: mbxval.solve("four_bar", engine="a\nb"),
        "engine must be text without control",
    ),
    "mode a number": (lambda: mbxval.solve("four_bar", mode=5), "mode must be a str, got int 5"),
    "scenario bytes": (lambda: mbxval.solve(b"four_bar"), "scenario must be a scenario name or file"),
    "scenario None": (lambda: mbxval.solve(None), "scenario must be a scenario name or file"),
    "scenario empty": (lambda: mbxval.solve(""), "scenario must be a scenario name or file"),
    "scenario with a NUL": (lambda: mbxval.solve("four_bar\x00"), "scenario must be text without control"),
    "load a number": (lambda: mbxval.load_scenario(5), "name_or_file must be a scenario name or file"),
    "a parameter None": (
        lambda: mbxval.load_scenario("slider_crank", offset=None),
        "parameters['offset'] must be a number or a str, got NoneType None",
    ),
    "a parameter a list": (
        lambda: mbxval.solve("slider_crank", offset=[0.1]),
        "parameters['offset'] must be a number or a str, got list [0.1]",
    ),
    "label None": (
        lambda: mbxval.compare("four_bar", FRAME, label=None),
        "label must be a str, got NoneType",
    ),
    "label bytes": (
        lambda: mbxval.compare("four_bar", FRAME, label=b"mine"),
        "label must be a str, got bytes",
    ),
    "label too long": (
        lambda: mbxval.compare("four_bar", FRAME, label="x" * 300),
        f"label must be at most {MAX_LABEL_LENGTH} characters, got 300",
    ),
    "trajectory a number": (
        lambda: mbxval.compare("four_bar", 5),
        "trajectory must be a DataFrame or a CSV file's path",
    ),
    "trajectory an array": (
        lambda: mbxval.compare("four_bar", np.zeros((3, 3))),
        "trajectory must be a DataFrame or a CSV file's path",
    ),
    "compare's scenario a number": (
        lambda: mbxval.compare(5, FRAME),
        "scenario must be a scenario name or file",
    ),
    "run of a number": (
        lambda: mbxval.run(5),
        "scenarios must be a name, a list of names or None, got int 5",
    ),
    "None among the scenarios": (
        _run(scenarios=["four_bar", None]),
        "scenarios[1] must be a scenario name or file (a non-empty str or os.PathLike), got NoneType None",
    ),
    "engines a number": (_run(engines=5), "engines must be a name, a list of names or None"),
    "suite a list": (_run(suite=["quick"]), "suite must be a str, got list"),
    "repeats a float": (_run(repeats=10.5), "repeats must be an int or None, got float 10.5"),
    "warmup a bool": (_run(warmup=True), "warmup must be an int or None, got bool True"),
    "timeout a text": (_run(timeout="1"), "timeout must be a number (float or int) or None, got str '1'"),
    "run's steps a bool": (_run(steps=True), "steps must be an int or None, got bool True"),
    "rerun a number": (_run(rerun=1), "rerun must be True or False, got int 1"),
    "report a text": (_run(report="no"), "report must be True or False, got str 'no'"),
    "progress None": (_run(progress=None), "progress must be True or False, got NoneType None"),
    "parameters a text": (_run(parameters="offset=0.1"), "parameters must be a mapping"),
    "sweep a number value": (_run(sweep={"offset": 0.1}), "sweep['offset'] must be a str, got float 0.1"),
    "out empty": (_run(out=""), "out must be a path (a non-empty str or os.PathLike), got str ''"),
    "out bytes": (_run(out=b"/tmp/x"), "out must be a path"),
    "read_results None": (lambda: mbxval.read_results(None), "directory must be a path"),
    "an array's repr on one line": (
        lambda: mbxval.compare("four_bar", np.zeros((9, 9))),
        "trajectory must be a DataFrame or a CSV file's path (a non-empty str or os.PathLike), "
        "got ndarray array(",
    ),
}


@pytest.mark.parametrize("case", CASES)
def test_a_mistyped_argument_is_one_argument_error(case: str) -> None:
    call, expected = CASES[case]
    with pytest.raises(mbxval.ArgumentError) as raised:
        call()
    message = str(raised.value)
    assert len(message.splitlines()) == 1, message
    assert message.startswith(expected), message


def test_a_directory_that_holds_no_store_is_one_argument_error(tmp_path: Path) -> None:
    with pytest.raises(mbxval.ArgumentError, match=r"no results\.parquet in") as raised:
        mbxval.read_results(tmp_path)
    assert isinstance(raised.value.__cause__, FileNotFoundError)  # the cause is kept for a program


def test_a_refused_run_writes_nothing(tmp_path: Path) -> None:
    with pytest.raises(mbxval.ArgumentError, match="steps must be an int"):
        mbxval.run("four_bar", "reference", suite="quick", out=tmp_path / "r", steps=True)
    assert not (tmp_path / "r").exists()


def test_numbers_of_numpy_and_paths_are_taken(tmp_path: Path) -> None:
    """What the checks let through still works: numpy's numbers, a Path."""
    frame = mbxval.solve("four_bar", steps=np.int64(4), t_end=np.float64(0.05))
    np.testing.assert_allclose(frame["t"], np.linspace(0.0, 0.05, 5))
    path = tmp_path / "fb.csv"
    mbxval.solve("four_bar", steps=4).to_csv(path, index=False)
    assert mbxval.compare(Path("four_bar"), path, steps=4).iloc[0]["error_position"] < 1e-9
