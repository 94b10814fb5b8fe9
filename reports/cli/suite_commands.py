"""The harness's commands: run, report, check and bench."""

from __future__ import annotations

import argparse
import importlib
import math
import os
import re
import tempfile
from collections import Counter
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import adapters
import reports.cli.run_overrides as run_overrides
from reports import gate, suites
from reports.cli.usage import UsageError
from reports.run import NOT_INSTALLED, RunConfig, scratch, stop, sweep
from reports.store import WriterLock, committed, scenario_identity
from reports.suites import Suite
from scenarios import Scenario, limits
from scenarios import load as build_scenario

DEFAULT_OUT = "mbxval-report"
MAX_REPEATS = 1000
MAX_TIMEOUT = 86400.0  # seconds: one day per run
WORKERS_PER_CORE = 4
MAX_WORKERS = WORKERS_PER_CORE * (os.cpu_count() or 1)
"""Local worker processes past a few per core only queue behind each other, each holding the engines
in memory (about 300 MB): `--workers 1000` started nothing in two minutes."""
CLUSTER_ADDRESS = re.compile(r"^[a-z0-9+]+://[^\s/]+:(\d{1,5})$")


def _selection(args: argparse.Namespace) -> tuple[Suite, list[str], list[str]]:
    """The suite, its scenarios (or the --scenario ones) and the engines (or the --engine ones)."""
    try:
        suite = suites.get(args.suite)
    except KeyError as error:
        raise UsageError(error.args[0]) from error
    names = args.scenario or suite.scenarios()
    for name in args.scenario:
        build_scenario(name)  # an unknown name fails here, with the known ones listed
    specs = getattr(args, "sweep", [])
    if specs:
        if not args.scenario:
            raise UsageError("--sweep needs the scenarios to sweep: give them with --scenario")
        try:
            names = sweep.points(names, specs)
        except sweep.SweepError as error:
            raise UsageError(str(error)) from error
        for name in names:
            build_scenario(name)  # a combination no single range excludes fails here, before any run
    names = run_overrides.apply(names, run_overrides.overrides(args))
    unknown = [e for e in args.engine if e not in adapters.names()]
    if unknown:
        raise UsageError(f"unknown engine '{unknown[0]}'; known: {', '.join(adapters.names())}")
    engines = args.engine or adapters.names()
    built = [build_scenario(name) for name in names]
    grids = [(s.steps + 1.0, len(s.bodies)) for s in built]
    limits.check_kept([grid for grid in grids for _ in range(len(engines) + 1)])  # before any run
    for scenario in built:  # the engines' own solves and the native forces are dense
        limits.check_grid(scenario.name, scenario.steps + 1, len(scenario.bodies), dense=True)
    return suite, names, engines


def _run_config(args: argparse.Namespace, suite: Suite, rerun: bool) -> RunConfig:
    """The run's configuration, each value checked against its range (UsageError naming it)."""
    repeats = suite.repeats if args.repeats is None else args.repeats
    warmup = suite.warmup if args.warmup is None else args.warmup
    timeout = suite.timeout if args.timeout is None else args.timeout
    if not 1 <= repeats <= MAX_REPEATS:
        raise UsageError(f"--repeats must be in [1, {MAX_REPEATS}], got {repeats}")
    if not 0 <= warmup <= MAX_REPEATS:
        raise UsageError(f"--warmup must be in [0, {MAX_REPEATS}], got {warmup}")
    if not (math.isfinite(timeout) and 0 < timeout <= MAX_TIMEOUT):
        raise UsageError(f"--timeout must be in (0, {MAX_TIMEOUT:g}] seconds, got {timeout}")
    return RunConfig(
        ladder=suite.ladder,
        repeats=repeats,
        warmup=warmup,
        timeout=timeout,
        rerun=rerun,
        keep_failures=args.keep_failures,
        keep_stale=args.keep_stale,
    )


@dataclass(frozen=True)
class Backend:
    """Where the runs happen: here one by one (neither set), on a local Dask cluster of `workers`
    processes, or on the Dask scheduler at `cluster`."""

    workers: int | None = None
    cluster: str | None = None


def _backend(args: argparse.Namespace) -> Backend:
    workers, cluster = getattr(args, "workers", None), getattr(args, "cluster", None)
    if workers is not None and cluster is not None:
        raise UsageError("--workers starts a local cluster and --cluster names one: give one of them")
    if workers is not None and not 1 <= workers <= MAX_WORKERS:
        raise UsageError(f"--workers must be in [1, {MAX_WORKERS}], got {workers}")
    address = CLUSTER_ADDRESS.match(cluster) if cluster is not None else None
    if cluster is not None and not (address and 1 <= int(address.group(1)) <= 65535):
        raise UsageError(
            "--cluster expects a scheduler address tcp://HOST:PORT with a port in [1, 65535], "
            f"got '{cluster[:200]}'"
        )
    return Backend(workers, cluster)


@dataclass(frozen=True)
class Selection:
    """A checked selection: what to run and how, before anything is written."""

    suite: Suite
    names: list[str]
    engines: list[str]
    config: RunConfig
    backend: Backend = Backend()


def select(args: argparse.Namespace, out: Path, rerun: bool = False) -> Selection:
    """The selection and run configuration of the command line, checked (UsageError) before any write."""
    suite, names, engines = _selection(args)
    if out.exists() and not out.is_dir():
        raise UsageError(f"--out {out} is a file, not a directory")
    config = _run_config(args, suite, rerun or args.rerun)
    check_scenario_names(names, out, config.rerun)
    return Selection(suite, names, engines, config, _backend(args))


def check_scenario_names(names: list[str], out: Path, rerun: bool) -> None:
    """Refuse (UsageError) two different mechanisms under one scenario name: two of this run, or
    one of this run (a family, a point or a file) and what the store in `out` holds under its name
    under another digest, whichever came first (unless `rerun` replaces those rows)."""
    given = {name: build_scenario(name) for name in names}
    clash = scenario_identity.name_clash(given)
    if clash is None and not rerun and committed(out) is not None:
        rows = stored_identities(out)
        found = (scenario_identity.stored_clash(rows, n, given[n], str(out)) for n in names)
        clash = next((f"{c}, or add --rerun to replace those results" for c in found if c), None)
    if clash is not None:
        raise UsageError(clash)


def stored_identities(results: Path | str) -> list[dict[str, Any]]:
    """Each scenario name the store holds with each digest its rows record, once."""
    from reports.store import read_results  # pandas: imported when a store is read

    frame = read_results(results)[0].reindex(columns=["scenario", "scenario_digest"]).fillna("")
    return frame.drop_duplicates().to_dict("records")  # type: ignore[no-any-return]


def run_selection(selection: Selection, out: Path, progress: bool, draw: bool = False) -> Counter[str]:
    """Run a checked selection into `out` (the caller holds its writer lock), and with `draw` draw
    its mechanisms beside the results for a report; returns the rows this run made, by status (the
    store may hold more: rows kept from earlier runs)."""
    from reports.run import Runner
    from reports.store import ResultsStore

    suite, backend = selection.suite, selection.backend
    arguments: dict[str, Any] = {
        "truth": suite.truth,
        "progress": progress,
        "suite": suite.name,
        "settings": suite.settings,
    }
    if backend == Backend():
        runner = Runner(ResultsStore(out), selection.engines, selection.config, **arguments)
    else:  # Dask is imported only here
        from reports.run import DaskRunner

        runner = DaskRunner(
            ResultsStore(out), selection.engines, selection.config, **arguments, **vars(backend)
        )
    runner.run(selection.names)
    record_verdicts(out, suite.name)
    if draw:
        _draw(out, runner.planned.values())
    return runner.made


def record_verdicts(out: Path, suite: str) -> None:
    """Decide, now the suite's runs are stored, what the report shows of them and store it with
    them (reports.stress.recording, reports.dynamics.recording, reports.run.recording): the
    stored results read back as a report reads them, so that a verdict is the one the stored
    trajectories give. The caller holds the store's writer lock."""
    from reports.dynamics import recording as dynamics_recording  # the native solver: imported when needed
    from reports.run import recording as harness_recording
    from reports.store import ResultsStore
    from reports.stress import recording as stress_recording

    store = ResultsStore(out)
    recorded = stress_recording.record(store, suite) + dynamics_recording.record(store)
    if recorded + harness_recording.record(store):
        store.save(store.meta, clean=True)


def _draw(out: Path, planned: Iterable[Scenario]) -> None:
    """The run's mechanisms drawn beside its results for the report (reports.drawing.files),
    imported when needed: it poses them with the native solver."""
    from reports.drawing import files as drawing_files

    drawing_files.write_drawings(out, planned)


def run_summary(made: Counter[str], out: Path, page: Path | None) -> str:
    """The last line of a run: this run's rows by status, then the store's total apart."""
    from reports.store import read_results

    counts = ", ".join(f"{status} {n}" for status, n in made.most_common())
    frame = read_results(out)[0]
    made_now = f"{made.total()} runs ({counts or 'all stored already'})"
    drifted = int((frame["self_check"].fillna("") != "").sum()) if "self_check" in frame else 0
    flagged = (
        f", {drifted} of them ok but drifted by their own figures (marked in the report)" if drifted else ""
    )
    return f"{made_now}; {out} holds {len(frame)} rows{flagged}; report: {page}"


def render_reports(results: Path | str, out: str | None = None) -> Path:
    """reports.render.report.render_reports, imported when needed: matplotlib is slow to import."""
    from reports.render import render_reports as render

    return render(results, out)


def run_and_render(
    selection: Selection, out: Path, wait: bool, progress: bool, report: bool = True
) -> tuple[Counter[str], Path | None]:
    """Run a checked selection into `out` under its writer lock, then render its report (unless
    not `report`); the rows this run made by status, and the report's page."""
    with WriterLock(out, wait=wait):
        made = run_selection(selection, out, progress, draw=report)
        return made, render_reports(out) if report else None


def cmd_run(args: argparse.Namespace) -> int:
    out = Path(args.out)
    selection = select(args, out)
    try:
        made, page = run_and_render(selection, out, args.wait, progress=not args.quiet)
    except KeyboardInterrupt as error:
        return stop.interrupted(
            f"interrupted; the runs made so far are stored in {out}: run again to resume", error
        )
    print(run_summary(made, out, page))
    return 0


def cmd_report(args: argparse.Namespace) -> int:
    if args.out is not None and Path(args.out).exists() and not Path(args.out).is_dir():
        raise UsageError(f"--out {args.out} is a file, not a directory")
    try:
        mixed = scenario_identity.mixed_names(stored_identities(args.results), args.results)
        if mixed is not None:
            raise UsageError(mixed)
        page = render_reports(args.results, args.out)
    except FileNotFoundError as error:
        raise UsageError(str(error)) from error
    print(f"report: {page}")
    return 0


def cmd_check(args: argparse.Namespace) -> int:
    """The gate runs what it compares (every selected run made afresh) unless --results is given."""
    if not (math.isfinite(args.factor) and args.factor > 0):
        raise UsageError(f"--factor must be a finite positive number, got {args.factor}")
    if args.update and (args.junit or args.json):
        raise UsageError("--junit and --json write a comparison; --update writes the baseline instead")
    for option, target in (("--junit", args.junit), ("--json", args.json)):  # before running anything
        if target is not None and (Path(target).is_dir() or not Path(target).parent.is_dir()):
            raise UsageError(f"{option} {target}: not a file in an existing directory")
    args.baseline = str(gate.baselines.resolve(args.baseline))
    if args.update:
        gate.updatable_cells(args.baseline)  # not a regular file, or not a baseline: before running
    baseline = None if args.update else gate.read_baseline(args.baseline)  # bad baseline: before running
    if args.results is not None:
        return _check(args, Path(args.results), baseline)
    out = Path(args.out) if args.out is not None else None
    selection = select(args, out or Path(tempfile.gettempdir()), rerun=True)
    if out is not None:
        with WriterLock(out, wait=args.wait):
            run_selection(selection, out, progress=not args.quiet)
            return _check(args, out, baseline)
    with scratch.scratch("check") as temporary:  # swept by the next check if a kill -9 leaves it
        results = Path(temporary) / "results"
        run_selection(selection, results, progress=not args.quiet)
        return _check(args, results, baseline)


def _check(args: argparse.Namespace, directory: Path, baseline: list[dict[str, Any]] | None) -> int:
    """Compare the results in `directory` with the baseline, or write the baseline (--update)."""
    from reports.store import read_results

    frame, meta = read_results(directory)
    absent = [engine for engine, version in meta.get("engines", {}).items() if version == NOT_INSTALLED]
    if baseline is None:
        print(gate.update_baseline(args.baseline, frame, meta, absent))
        return 0
    verdict = gate.judge(baseline, frame, args.factor, absent)
    if args.junit:
        gate.files.write(args.junit, gate.files.junit_xml(verdict, args.baseline, args.factor))
    if args.json:
        gate.files.write(args.json, gate.files.verdict_json(verdict, args.baseline, args.factor))
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
    parser.add_argument(
        "--keep-failures", action="store_true", help="keep stored failed/timeout rows (default: retry them)"
    )
    parser.add_argument(
        "--keep-stale",
        action="store_true",
        help="keep rows made under another revision or engine version, marked stale (default: rerun them)",
    )
    parser.add_argument("--wait", action="store_true", help="wait for another run writing --out to end")


BENCHMARKS = {
    "speed": "benchmarks.solver_speed",
    "scaling": "benchmarks.chain_scaling",
    "sweep": "benchmarks.sweep_speed",
    "overhead": "benchmarks.run_overhead",
    "breakdown": "benchmarks.run_breakdown",
    "repeats": "benchmarks.repeat_noise",
    "dynamics": "benchmarks.dynamics_speed",
    "store": "benchmarks.store_append",
    "mutation": "benchmarks.mutation",
    "startup": "benchmarks.startup",
    "threads": "benchmarks.blas_threads",
}


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
    run_overrides.add_arguments(run)
    run.add_argument(
        "--sweep",
        action="append",
        default=[],
        metavar="NAME=SPEC",
        help="sweep a parameter of the --scenario ones: log:LOW:HIGH:N, lin:LOW:HIGH:N or A,B,... "
        "(repeatable: the grid of every --sweep)",
    )
    where = run.add_mutually_exclusive_group()
    where.add_argument("--workers", type=int, help="run on a local Dask cluster of N worker processes")
    where.add_argument("--cluster", metavar="ADDRESS", help="run on the Dask scheduler at tcp://HOST:PORT")

    report = sub.add_parser("report", help="re-render the report from stored results")
    report.add_argument("results", help="results directory (or its results.parquet)")
    report.add_argument("--out", help="directory for index.html and summary.md (default: RESULTS)")

    check = sub.add_parser("check", help="regression gate: compare results with a baseline (exit 1 if worse)")
    check.add_argument(
        "--baseline",
        required=True,
        help=f"baseline JSON file, or a shipped one by name ({', '.join(gate.baselines.names())})",
    )
    check.add_argument("--junit", metavar="FILE", help="also write the verdict as JUnit XML, a test per cell")
    check.add_argument("--json", metavar="FILE", help="also write the verdict as JSON")
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
        help="speed: cost per time point per family; scaling: cost against chain size; "
        "sweep: a 200-point sweep serial against --workers; overhead: wall time against the measured work; "
        "breakdown: where a run phase's overhead goes, step by step (--scenario, --engine, --sweep); "
        "repeats: how far apart timed repeats are, and what stopping where two agree saves; "
        "store: a save of 100 rows onto stores of 1k, 10k and 100k rows, whole rewrite against append; "
        "mutation: mutmut over a module with its own tests (--module PATH); "
        "startup: CPU, wall and memory of --help, a start-up, a 16-point sweep, Andrews and A02 from a fresh "
        "process, with and without OPENBLAS_NUM_THREADS=1; threads: the native solver with one BLAS thread "
        "beside the library's default",
    )
    bench.add_argument("options", nargs=argparse.REMAINDER, help="passed to the benchmark (see its --help)")


COMMANDS: dict[str, Callable[[argparse.Namespace], int]] = {
    "run": cmd_run,
    "report": cmd_report,
    "check": cmd_check,
    "bench": cmd_bench,
}
