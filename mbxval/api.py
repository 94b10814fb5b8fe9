"""The Python API: the command line's own steps (reports.cli), called with Python values.

Each function checks every argument's type where it enters (mbxval.arguments), then its values
exactly as the matching command does, and raises what the command would report as
`mbxval: error: ...`: ArgumentError (a ValueError) or ScenarioError (a ValueError too) with the same
message.
"""

from __future__ import annotations

import os
import shutil
import tempfile
from collections.abc import Iterator, Mapping, Sequence
from contextlib import contextmanager
from pathlib import Path

import pandas as pd

import mbxval.arguments as check
from adapters import NATIVE
from adapters.base import OptionValue
from mbxval.arguments import ArgumentError
from reports.cli import UsageError, check_label, parser, run_and_render, select, solve_trajectory
from reports.run import ImportedTrajectory, TrajectoryFileError, parse_trajectory, read_trajectory, score
from reports.store import StoreBusy, StoreDamaged
from reports.store import read_results as read_stored
from scenarios import Scenario
from scenarios import load as load_by_name
from scenarios.limits import MAX_LABEL_LENGTH
from scenarios.names import check_scenario_names

__all__ = ["ArgumentError", "compare", "load_scenario", "read_results", "run", "solve"]

Value = float | int | str
"""A parameter's value: given as a number or as the text `--set` would take."""
PathLike = str | os.PathLike[str]


@contextmanager
def _checked() -> Iterator[None]:
    """What the command line reports as one line (bad input, a store that is damaged or busy, a
    path it cannot use) as an ArgumentError, with its message."""
    try:
        yield
    except (UsageError, StoreDamaged, StoreBusy) as error:
        raise ArgumentError(str(error)) from None
    except OSError as error:
        raise ArgumentError(str(error)) from error


def _texts(values: Mapping[str, str]) -> list[str]:
    """`NAME=VALUE` texts, as the command line takes them."""
    return [f"{key}={value}" for key, value in values.items()]


def load_scenario(name_or_file: str | PathLike, **parameters: Value) -> Scenario:
    """The scenario a built-in name (`four_bar`, `slider_crank/offset`, the bracket form
    `slider_crank[offset=0.05]`) or a scenario file (`*.toml`) describes, with parameters set as
    `--set` sets them: a family's by name, a file's by dotted key path (pass those as
    `**{"bodies.crank.mass": 2.0}`), and the grid keys `t_end` and `steps` for every scenario.
    Raises ScenarioError naming an unknown scenario or parameter, or a value out of its range."""
    name = check.scenario_name("name_or_file", name_or_file)
    return load_by_name(name, check.mapping("parameters", parameters, check.scenario_value))


def _scenario(scenario: object, parameters: Mapping[str, Value]) -> Scenario:
    if not isinstance(scenario, Scenario):
        return load_scenario(check.scenario_name("scenario", scenario), **parameters)
    if parameters:
        raise ArgumentError(f"parameters {', '.join(parameters)} given with a built Scenario: set them in it")
    return check_scenario_names(scenario)  # its names are checked as a file's would be


def solve(
    scenario: str | PathLike | Scenario,
    engine: str = NATIVE,
    mode: str | None = None,
    settings: Mapping[str, OptionValue] | None = None,
    t_end: float | None = None,
    steps: int | None = None,
    **parameters: Value,
) -> pd.DataFrame:
    """The canonical trajectory of `scenario` by one engine, as `mbxval solve` writes it: column `t`
    (steps + 1 rows over [0, t_end], each default the scenario's), then `<body>.x .y .theta .vx .vy
    .omega .ax .ay .alpha` for every output body, then the extras the engine writes.

    `mode` and `settings` choose the engine's setting (`settings={"dt": 1e-4}`; the engine's default
    otherwise); `parameters` set the scenario's as in `load_scenario`. Raises ArgumentError for an
    unknown engine, mode or setting, a grid out of range, or a run that ends other than ok (its
    status and message), and ScenarioError for a scenario that cannot be built."""
    engine, mode = check.text("engine", engine), check.optional_text("mode", mode)
    options = _texts(check.mapping("settings", settings, check.option_value))
    grid = (check.real("t_end", t_end), check.whole("steps", steps), None)
    built = _scenario(scenario, parameters)
    with _checked():
        trajectory = solve_trajectory(built, engine, mode, options, grid)
    return trajectory.to_frame()


def run(
    scenarios: Sequence[str | PathLike] | str | PathLike | None = None,
    engines: Sequence[str] | str | None = None,
    *,
    suite: str = "default",
    out: PathLike | None = None,
    t_end: float | None = None,
    steps: int | None = None,
    parameters: Mapping[str, Value] | None = None,
    sweep: Mapping[str, str] | None = None,
    repeats: int | None = None,
    warmup: int | None = None,
    timeout: float | None = None,
    rerun: bool = False,
    report: bool = True,
    progress: bool = False,
) -> pd.DataFrame:
    """Run the harness as `mbxval run` does and return the results table of `out`: one row per run
    (the rows stored there before are kept, and returned too, unless `rerun`).

    `scenarios` and `engines` narrow the `suite` (default: all of its scenarios, every engine);
    `t_end`, `steps` and `parameters` apply to every scenario (each becomes a bracket point such as
    `slider_crank[offset=0.05]`); `sweep` maps a parameter to a spec (`"log:1e-3:1e-1:5"`, `"a,b"`).
    `out` defaults to a new temporary directory; the directory is `frame.attrs["results"]`, and with
    `report` it holds index.html. Raises ArgumentError or ScenarioError before anything runs."""
    args = parser().parse_args(["run"])
    args.scenario = check.names("scenarios", scenarios, check.scenario_name)
    args.engine = check.names("engines", engines, check.text)
    args.suite = check.text("suite", suite)
    args.t_end, args.timeout = check.real("t_end", t_end), check.real("timeout", timeout)
    args.steps, args.repeats = check.whole("steps", steps), check.whole("repeats", repeats)
    args.warmup = check.whole("warmup", warmup)
    args.rerun, report = check.flag("rerun", rerun), check.flag("report", report)
    progress = check.flag("progress", progress)
    args.set = _texts(check.mapping("parameters", parameters, check.scenario_value))
    args.sweep = _texts(check.mapping("sweep", sweep, check.text))
    target = Path(tempfile.mkdtemp(prefix="mbxval-run-")) if out is None else Path(check.path("out", out))
    args.out = str(target)
    try:
        with _checked():
            selection = select(args, target)
            run_and_render(selection, target, wait=False, progress=progress, report=report)
    except BaseException:
        if out is None:
            shutil.rmtree(target, ignore_errors=True)  # the temporary directory made above
        raise
    return read_results(target)


def compare(
    scenario: str | PathLike | Scenario,
    trajectory: pd.DataFrame | PathLike,
    label: str = "trajectory",
    **parameters: Value,
) -> pd.DataFrame:
    """Score a trajectory made by any tool as `mbxval compare` does: against the scenario's truth,
    with the runs' metrics. `trajectory` is a DataFrame or a CSV file with the columns `solve`
    gives (bodies and levels may be missing) on the scenario's time grid. Returns the scored row
    (one row; `error_position`, `error_velocity`, `error_acceleration`, `truth`, ...). Raises
    ArgumentError for a trajectory that cannot be scored (the message says why)."""
    label = check.text("label", label, MAX_LABEL_LENGTH)
    if not isinstance(trajectory, pd.DataFrame):
        trajectory = check.path("trajectory", trajectory, "a DataFrame or a CSV file's path")
    built = _scenario(scenario, parameters)
    with _checked():
        check_label(label)
        if isinstance(trajectory, pd.DataFrame):
            imported = _read_frame(trajectory, built)
        else:
            imported = _read_file(trajectory, built)
    return pd.DataFrame([score(built, imported, label).row])


def _read_file(path: str, scenario: Scenario) -> ImportedTrajectory:
    try:
        return read_trajectory(path, scenario)
    except TrajectoryFileError as error:
        raise ArgumentError(str(error)) from None


def _read_frame(frame: pd.DataFrame, scenario: Scenario) -> ImportedTrajectory:
    """The frame checked as its CSV text, in memory, by the CSV reader: every check a file gets,
    and nothing written anywhere."""
    source = "the trajectory DataFrame"
    try:
        return parse_trajectory(frame.to_csv(index=False, float_format="%.17g"), source, scenario)
    except TrajectoryFileError as error:
        raise ArgumentError(str(error)) from None


def read_results(directory: PathLike) -> pd.DataFrame:
    """The results table stored in `directory` (by `run`, `mbxval run` or `mbxval compare --out`),
    verified against its checksums; the sidecar (machine, versions, revision, date) is
    `frame.attrs["meta"]` and the directory `frame.attrs["results"]`."""
    directory = check.path("directory", directory)
    with _checked():
        frame, meta = read_stored(directory)
    frame.attrs.update(meta=meta, results=str(directory))
    return frame
