"""The `mbxval` command line: list, solve, export, run, report, check.

Every failure the user can cause ends with one line `mbxval: error: ...` on stderr, exit status 2,
and no partial output file.
"""

from __future__ import annotations

import argparse
import importlib
import math
import sys
import tempfile
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import NoReturn

import numpy as np

import adapters
from adapters.base import Adapter, OptionValue, Setting
from reports import gate, suites
from reports.atomic_write import atomic_output
from reports.results_store import ResultsStore, read_results
from reports.runner import Runner, RunOptions
from reports.suites import Suite
from scenarios import Scenario, ScenarioError, catalogue, families
from scenarios import build as build_scenario

DEFAULT_OUT = "mbxval-report"


class UsageError(Exception):
    """Bad input from the user: reported as one line with exit status 2."""


class _Parser(argparse.ArgumentParser):
    """argparse with its errors on one line, like every other error of mbxval."""

    def error(self, message: str) -> NoReturn:
        self.exit(2, f"mbxval: error: {message} (see `{self.prog} --help`)\n")


def _pairs(items: Sequence[str], what: str) -> dict[str, str]:
    pairs = {}
    for item in items:
        key, sep, value = item.partition("=")
        if not sep or not key:
            raise UsageError(f"{what} expects NAME=VALUE, got '{item}'")
        pairs[key] = value
    return pairs


def _option_value(text: str) -> OptionValue:
    for kind in (int, float):
        try:
            return kind(text)  # type: ignore[no-any-return]
        except ValueError:
            pass
    return text


def load_engine(name: str) -> Adapter:
    try:
        return adapters.load(name)
    except adapters.EngineUnavailable as error:
        raise UsageError(str(error)) from error


def time_grid(scenario: Scenario, t_end: float | None, steps: int | None, dt: float | None) -> np.ndarray:
    """The output grid: `steps` equal steps over [0, t_end], or multiples of `dt` up to t_end."""
    t_end = scenario.t_end if t_end is None else t_end
    if not (math.isfinite(t_end) and t_end > 0):
        raise UsageError(f"--t-end must be a positive number, got {t_end}")
    if dt is not None:
        if not (math.isfinite(dt) and 0 < dt <= t_end):
            raise UsageError(f"--dt must be positive and at most --t-end, got {dt}")
        steps = math.floor(t_end / dt + 1e-9)
        return dt * np.arange(steps + 1)
    steps = scenario.steps if steps is None else steps
    if steps < 1:
        raise UsageError(f"--steps must be at least 1, got {steps}")
    return np.linspace(0.0, t_end, steps + 1)


def engine_setting(adapter: Adapter, scenario: Scenario, mode: str | None, options: list[str]) -> Setting:
    """The engine's default setting for the scenario, with a mode and options overridden."""
    setting = adapter.default_setting(scenario)
    if mode is not None:
        setting = Setting(mode, setting.options)
    overrides = {k: _option_value(v) for k, v in _pairs(options, "--setting").items()}
    return setting.replace(**overrides) if overrides else setting


def cmd_list(args: argparse.Namespace) -> int:
    """A scenario x engine table of what each engine supports, the reasons below it, then each
    family's parameters with their defaults."""
    engines = {}
    for name in adapters.names():
        try:
            engines[name] = adapters.load(name)
        except adapters.EngineUnavailable as error:
            print(f"engine {name}: unavailable ({error})")
    print("engines: " + ", ".join(f"{n} {a._safe_version()}" for n, a in engines.items()))
    names = catalogue(include_stress=args.stress)
    width = max(len(n) for n in names) + 2
    print("\n" + "scenario".ljust(width) + "".join(e.ljust(12) for e in engines))
    reasons: list[str] = []
    for name in names:
        scenario = build_scenario(name)
        cells = []
        for engine, adapter in engines.items():
            reason = adapter.supports(scenario)
            if reason is None:
                cells.append("yes")
            else:
                reasons.append(f"[{len(reasons) + 1}] {engine} on {name}: {reason}")
                cells.append(f"no [{len(reasons)}]")
        print(name.ljust(width) + "".join(c.ljust(12) for c in cells))
    if reasons:
        print("\n" + "\n".join(reasons))
    print("\nparameters (defaults); set them with --set NAME=VALUE:")
    for fam in families().values():
        print(f"  {fam.name}: " + " ".join(f"{k}={v}" for k, v in fam.defaults.items()))
    return 0


def cmd_solve(args: argparse.Namespace) -> int:
    scenario = build_scenario(args.scenario, overrides=_pairs(args.set, "--set"))
    grid = time_grid(scenario, args.t_end, args.steps, args.dt)
    adapter = load_engine(args.engine)
    setting = engine_setting(adapter, scenario, args.mode, args.setting)
    result = adapter.run(scenario, setting, grid)
    if result.status != "ok" or result.trajectory is None:
        when = "" if result.failure_time is None else f" at t={result.failure_time:.6g}"
        raise UsageError(f"{args.engine} {result.status}{when}: {result.message}")
    trajectory = result.trajectory.select(scenario.output_bodies)
    if args.out is None:
        trajectory.write_csv(sys.stdout)
    else:
        with atomic_output(args.out) as stream:
            trajectory.write_csv(stream)
    return 0


def cmd_export(args: argparse.Namespace) -> int:
    scenario = build_scenario(args.scenario, overrides=_pairs(args.set, "--set"))
    adapter = load_engine(args.engine)
    setting = engine_setting(adapter, scenario, args.mode, args.setting)
    reason = adapter.supports(scenario)
    if reason is not None:
        raise UsageError(f"{args.engine} cannot represent {scenario.name}: {reason}")
    try:
        adapter.export(scenario, setting, args.out)
    except NotImplementedError as error:
        raise UsageError(str(error)) from error
    print(f"wrote {args.out}")
    return 0


def _selection(args: argparse.Namespace) -> tuple[Suite, list[str], list[str]]:
    """The suite, its scenarios (or the --scenario ones) and the engines (or the --engine ones)."""
    try:
        suite = suites.get(args.suite)
    except KeyError as error:
        raise UsageError(error.args[0]) from error
    names = args.scenario or suite.scenarios()
    for name in args.scenario:
        build_scenario(name)  # an unknown name fails here, with the known ones listed
    unknown = [e for e in args.engine if e not in adapters.names()]
    if unknown:
        raise UsageError(f"unknown engine '{unknown[0]}'; known: {', '.join(adapters.names())}")
    return suite, names, args.engine or adapters.names()


def run_selection(args: argparse.Namespace, out: Path, progress: bool) -> Path:
    """Run the selected scenarios and engines into `out`; returns the results directory."""
    suite, names, engines = _selection(args)
    if out.exists() and not out.is_dir():
        raise UsageError(f"--out {out} is a file, not a directory")
    options = RunOptions(
        sweep=suite.sweep,
        repeats=suite.repeats if args.repeats is None else args.repeats,
        warmup=suite.warmup if args.warmup is None else args.warmup,
        timeout=suite.timeout if args.timeout is None else args.timeout,
        rerun=args.rerun,
    )
    runner = Runner(
        ResultsStore(out),
        engines,
        options,
        truth=suite.truth,
        progress=progress,
        suite=suite.name,
        settings=suite.settings,
    )
    runner.run(names)
    return out


def render_reports(results: Path | str, out: str | None = None) -> Path:
    """reports.report.render_reports, imported when needed: matplotlib is slow to import."""
    from reports.report import render_reports as render

    return render(results, out)


def cmd_run(args: argparse.Namespace) -> int:
    try:
        out = run_selection(args, Path(args.out), progress=not args.quiet)
    except KeyboardInterrupt:
        print(
            f"mbxval: interrupted; the runs made so far are stored in {args.out}: run again to resume",
            file=sys.stderr,
        )
        return 130
    page = render_reports(out)
    frame, _ = read_results(out)
    counts = ", ".join(f"{k} {v}" for k, v in frame["status"].value_counts().items())
    print(f"{len(frame)} runs ({counts}); report: {page}")
    return 0


def cmd_report(args: argparse.Namespace) -> int:
    try:
        page = render_reports(args.results, args.out)
    except (FileNotFoundError, ValueError) as error:
        raise UsageError(str(error)) from error
    print(f"report: {page}")
    return 0


def cmd_check(args: argparse.Namespace) -> int:
    if args.results is not None:
        return _check(args, Path(args.results))
    if args.out is not None:
        return _check(args, run_selection(args, Path(args.out), progress=not args.quiet))
    with tempfile.TemporaryDirectory(prefix="mbxval-check-") as temporary:
        return _check(args, run_selection(args, Path(temporary), progress=not args.quiet))


def _check(args: argparse.Namespace, directory: Path) -> int:
    """Compare the results in `directory` with the baseline, or write the baseline (--update)."""
    try:
        frame, meta = read_results(directory)
        if args.update:
            gate.write_baseline(args.baseline, frame, meta)
            print(f"wrote baseline {args.baseline} from {directory} ({len(frame)} cells)")
            return 0
        verdict = gate.compare(gate.read_baseline(args.baseline), frame, args.factor)
    except (FileNotFoundError, ValueError, KeyError) as error:
        raise UsageError(f"{type(error).__name__}: {error}") from error
    print(gate.describe(verdict, args.baseline, args.factor))
    return 0 if verdict.passed else 1


def _selection_arguments(parser: argparse.ArgumentParser, suite: str) -> None:
    parser.add_argument("--suite", default=suite, help=f"suite ({', '.join(suites.SUITES)}; default {suite})")
    parser.add_argument("--scenario", action="append", default=[], help="run only this scenario (repeatable)")
    parser.add_argument("--engine", action="append", default=[], help="run only this engine (repeatable)")
    parser.add_argument("--repeats", type=int, help="timed repeats per run (default: the suite's)")
    parser.add_argument("--warmup", type=int, help="untimed warm-up runs (default: the suite's)")
    parser.add_argument("--timeout", type=float, help="time limit per run in seconds (default: the suite's)")
    parser.add_argument("--rerun", action="store_true", help="redo runs already stored in the directory")


def _scenario_arguments(parser: argparse.ArgumentParser, engine_default: str) -> None:
    parser.add_argument("scenario", help="scenario name, or family/variant (see `mbxval list`)")
    parser.add_argument("--engine", default=engine_default, help=f"engine (default {engine_default})")
    parser.add_argument("--set", action="append", default=[], metavar="NAME=VALUE", help="scenario parameter")
    parser.add_argument("--mode", help="engine mode (for example RK4, implicitfast, kinematic)")
    parser.add_argument(
        "--setting",
        action="append",
        default=[],
        metavar="KEY=VALUE",
        help="engine setting, such as dt=1e-4",
    )


def parser() -> argparse.ArgumentParser:
    top = _Parser(prog="mbxval", description=__doc__.splitlines()[0])
    sub = top.add_subparsers(dest="command", required=True, parser_class=_Parser)

    listing = sub.add_parser("list", help="scenarios, variants, engines and what each supports")
    listing.add_argument("--stress", action="store_true", help="include the stress variants")

    solve = sub.add_parser("solve", help="one trajectory as CSV")
    _scenario_arguments(solve, "reference")
    solve.add_argument("--t-end", type=float, help="end time (default: the scenario's)")
    grid = solve.add_mutually_exclusive_group()
    grid.add_argument("--steps", type=int, help="number of equal steps (rows = steps + 1)")
    grid.add_argument("--dt", type=float, help="output step")
    solve.add_argument("--out", help="CSV file (default: stdout)")

    export = sub.add_parser("export", help="write the engine's own model file")
    _scenario_arguments(export, "mujoco")
    export.add_argument("--out", required=True, help="model file to write")

    run = sub.add_parser("run", help="run a suite on every engine, store results, render the report")
    _selection_arguments(run, "default")
    run.add_argument("--out", default=DEFAULT_OUT, help=f"output directory (default {DEFAULT_OUT})")
    run.add_argument("--quiet", action="store_true", help="no progress bar")

    report = sub.add_parser("report", help="re-render the report from stored results")
    report.add_argument("results", help="results directory (or its results.parquet)")
    report.add_argument("--out", help="directory for index.html and summary.md (default: RESULTS)")

    check = sub.add_parser("check", help="regression gate: compare results with a baseline (exit 1 if worse)")
    check.add_argument("--baseline", required=True, help="baseline JSON file (see baselines/)")
    check.add_argument("--results", help="compare these stored results instead of running the suite")
    _selection_arguments(check, "quick")
    check.add_argument("--out", help="directory for the results of the run (default: a temporary one)")
    check.add_argument("--factor", type=float, default=gate.DEFAULT_FACTOR, help="allowed error growth")
    check.add_argument("--update", action="store_true", help="write the baseline from the results instead")
    check.add_argument("--quiet", action="store_true", help="no progress bar")

    bench = sub.add_parser("bench", help="speed of the native solver against the engines (benchmarks/)")
    bench.add_argument(
        "which",
        nargs="?",
        choices=sorted(BENCHMARKS),
        default="speed",
        help="speed: cost per time point per family; scaling: cost against chain size",
    )
    bench.add_argument("options", nargs=argparse.REMAINDER, help="passed to the benchmark (see its --help)")
    return top


BENCHMARKS = {"speed": "benchmarks.solver_speed", "scaling": "benchmarks.chain_scaling"}


def cmd_bench(args: argparse.Namespace) -> int:
    """Run one of the benchmark scripts, which print their own tables."""
    module = importlib.import_module(BENCHMARKS[args.which])
    module.main(list(args.options))
    return 0


COMMANDS: dict[str, Callable[[argparse.Namespace], int]] = {
    "list": cmd_list,
    "solve": cmd_solve,
    "export": cmd_export,
    "run": cmd_run,
    "report": cmd_report,
    "check": cmd_check,
    "bench": cmd_bench,
}


def main(argv: Sequence[str] | None = None) -> int:
    args = parser().parse_args(argv)
    try:
        return COMMANDS[args.command](args)
    except (UsageError, ScenarioError, OSError) as error:
        print(f"mbxval: error: {error}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
