"""The harness's commands: run, report, check and bench."""

from __future__ import annotations

import argparse
import importlib
import sys
import tempfile
from collections.abc import Callable
from pathlib import Path

import adapters
from reports.cli.usage import UsageError
from reports.harness import gate, suites
from reports.harness.results_store import ResultsStore, read_results
from reports.harness.runner import Runner, RunOptions
from reports.harness.suites import Suite
from scenarios import load as build_scenario

DEFAULT_OUT = "mbxval-report"


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
    """reports.render.report.render_reports, imported when needed: matplotlib is slow to import."""
    from reports.render.report import render_reports as render

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
        result = gate.compare(gate.read_baseline(args.baseline), frame, args.factor)
    except (FileNotFoundError, ValueError, KeyError) as error:
        raise UsageError(f"{type(error).__name__}: {error}") from error
    print(gate.describe(result, args.baseline, args.factor))
    return 0 if result.passed else 1


def _selection_arguments(parser: argparse.ArgumentParser, suite: str) -> None:
    parser.add_argument("--suite", default=suite, help=f"suite ({', '.join(suites.SUITES)}; default {suite})")
    parser.add_argument("--scenario", action="append", default=[], help="run only this scenario (repeatable)")
    parser.add_argument("--engine", action="append", default=[], help="run only this engine (repeatable)")
    parser.add_argument("--repeats", type=int, help="timed repeats per run (default: the suite's)")
    parser.add_argument("--warmup", type=int, help="untimed warm-up runs (default: the suite's)")
    parser.add_argument("--timeout", type=float, help="time limit per run in seconds (default: the suite's)")
    parser.add_argument("--rerun", action="store_true", help="redo runs already stored in the directory")


BENCHMARKS = {"speed": "benchmarks.solver_speed", "scaling": "benchmarks.chain_scaling"}


def cmd_bench(args: argparse.Namespace) -> int:
    """Run one of the benchmark scripts, which print their own tables."""
    module = importlib.import_module(BENCHMARKS[args.which])
    module.main(list(args.options))
    return 0


def add_parsers(sub: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    """Add the harness's subcommands (COMMANDS) to the command line."""
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


COMMANDS: dict[str, Callable[[argparse.Namespace], int]] = {
    "run": cmd_run,
    "report": cmd_report,
    "check": cmd_check,
    "bench": cmd_bench,
}
