"""Sweep grids from `--sweep`: log, linear and explicit axes, the grid of swept points and their
names, and every bad spec or out-of-range value refused as one line with status 2 before any run."""

from __future__ import annotations

import itertools
import math
import subprocess
import sys
from pathlib import Path

import pytest

from reports.cli.main import main
from reports.cli.suite_commands import MAX_WORKERS
from reports.run.sweep import SweepError, parse_axis, points
from scenarios import ScenarioError, load


def test_log_axis_spans_the_decades_in_equal_ratios() -> None:
    axis = parse_axis("omega=log:1e-3:1e4:8")
    values = [float(v) for v in axis.values]
    assert axis.name == "omega" and len(values) == 8
    assert values[0] == 1e-3 and values[-1] == 1e4
    ratios = [b / a for a, b in itertools.pairwise(values)]
    assert all(r == pytest.approx(10.0, rel=1e-5) for r in ratios)  # 7 decades in 7 steps


def test_linear_and_explicit_axes() -> None:
    assert parse_axis("crank_length=lin:0.05:0.2:4").values == ("0.05", "0.1", "0.15", "0.2")
    assert parse_axis("branch=1,-1").values == ("1", "-1")
    assert parse_axis("omega=lin:3:3:1").values == ("3",)


def test_the_grid_varies_the_first_axis_slowest_and_names_every_point() -> None:
    names = points(["four_bar"], ["crank_length=0.05,0.06", "omega=lin:10:30:3"])
    assert names == [
        f"four_bar[crank_length={a},omega={w}]" for a in ("0.05", "0.06") for w in ("10", "20", "30")
    ]
    scenario = load(names[4])
    assert scenario.name == names[4]  # the name rebuilds the point, and is the point's own
    assert scenario.parameter("crank_length") == 0.06 and scenario.parameter("omega") == 20.0
    assert scenario.t_end == pytest.approx(2 * math.pi / 20.0)


def test_an_integer_parameter_takes_rounded_values_once() -> None:
    assert points(["four_bar"], ["steps=lin:10:12:5"]) == [f"four_bar[steps={n}]" for n in (10, 11, 12)]


def test_a_variant_keeps_its_own_values_under_the_swept_ones() -> None:
    (name,) = points(["four_bar/crossed"], ["omega=7"])
    scenario = load(name)
    assert name == "four_bar/crossed[omega=7]" and scenario.parameter("branch") == -1


@pytest.mark.parametrize(
    ("spec", "words"),
    [
        ("omega", "--sweep expects NAME=SPEC"),
        ("omega=log:0:10:3", "log spacing needs positive bounds"),
        ("omega=lin:1:2", "lin:LOW:HIGH:N"),
        ("omega=lin:1:2:x", "lin:LOW:HIGH:N"),
        ("omega=lin:1:2:0", "N must be in"),
        ("omega=lin:1:2:1", "ambiguous"),
        ("omega=lin:1:nan:3", "finite"),
        ("omega=1,,2", "empty or malformed value"),
        ("omega=1,1", "given twice"),
        ("omega=lin:1:1.0000001:3", "significant digits"),
    ],
)
def test_bad_specs_are_refused(spec: str, words: str) -> None:
    with pytest.raises(SweepError, match=words):
        points(["four_bar"], [spec])


@pytest.mark.parametrize(
    ("spec", "words"),
    [
        (
            "crank_length=lin:-0.1:0.1:3",
            "four_bar: crank_length must be a number in (0, 1e+06] m, got '-0.1'",
        ),
        ("omega=0,1", "four_bar: omega must be a number in [-1e+06, 1e+06] rad/s, not 0, got '0'"),
        ("branch=0,1", "four_bar: branch must be an integer in [-1, 1], not 0"),
        ("speed=1,2", "four_bar: unknown parameter 'speed' in --sweep"),
    ],
)
def test_values_outside_the_declared_range_are_refused(spec: str, words: str) -> None:
    with pytest.raises(ScenarioError) as raised:
        points(["four_bar"], [spec])
    assert words in str(raised.value)


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["--scenario", "four_bar", "--sweep", "omega=log:-1:1:3"], "log spacing needs positive bounds"),
        (["--scenario", "four_bar", "--sweep", "crank_length=2e6"], "crank_length must be a number in"),
        (["--scenario", "four_bar", "--sweep", "omega=1", "--sweep", "omega=2"], "swept twice"),
        (["--sweep", "omega=1,2"], "--sweep needs the scenarios to sweep"),
        (["--scenario", "four_bar", "--workers", "0"], f"--workers must be in [1, {MAX_WORKERS}], got 0"),
        (["--scenario", "four_bar", "--cluster", "localhost"], "--cluster expects a scheduler address"),
        (["--scenario", "four_bar", "--workers", "2", "--cluster", "tcp://127.0.0.1:1"], "not allowed with"),
    ],
)
def test_the_command_line_refuses_them_in_one_line_before_anything_runs(
    args: list[str], words: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    try:
        status = main(["run", "--out", str(tmp_path / "out"), "--quiet", *args])
    except SystemExit as ended:  # argparse's own refusals end here, with the same one line
        status = ended.code  # type: ignore[assignment]
    assert status == 2
    error = capsys.readouterr().err
    assert error.startswith("mbxval: error: ") and words in error and error.count("\n") == 1
    assert not (tmp_path / "out").exists()


def test_the_serial_runner_does_not_import_dask(tmp_path: Path) -> None:
    """A serial run of the command line, in a fresh interpreter, leaves Dask unimported."""
    code = (
        "import sys\n"
        "from reports.cli.main import main\n"
        f"status = main(['run', '--out', {str(tmp_path)!r}, '--quiet', '--suite', 'quick',"
        " '--scenario', 'spur_gears', '--engine', 'reference', '--sweep', 'radius_in=0.04,0.05'])\n"
        "assert status == 0, status\n"
        "print(sorted(m for m in sys.modules if m.split('.')[0] in ('dask', 'distributed')))\n"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout.strip().splitlines()[-1] == "[]"
