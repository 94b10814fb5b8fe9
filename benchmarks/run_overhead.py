"""What the harness spends around the work it measures: wall time of `mbxval run` against the
work its own rows time, for a native sweep and for a subset of the default suite.

    python -m benchmarks.run_overhead [--points 16] [--scenarios 6] [--engines reference]
        [--sweep NAME=SPEC ...] [--suite quick] [--workers N]

Each case runs the command line in a fresh interpreter into an empty directory, as a user does
(start-up, truths, forked runs, saving, the report page), and reads the rows it stored:
- compute: the sum of the rows' build and run times (run time being the minimum of the repeats);
- work: what the rows measured their timing spent, build + warm-up + timed repeats per row (the
  wall-clock `build_time_wall`, `warmup_time_wall` and `repeats_time_wall` columns, each measured
  where it ran);
- overhead per run: (wall - work) / rows.
A run that fails in its engine (a singular position, a divergence) stores what it spent up to the
failure (adapters.spent), so its work counts as work; a timeout stores the limit it hit, a crash
no times.
Beside them, the wall time of a one-point `mbxval solve` of the same scenario, for the ratio the
issue's target names (the native sweep in at most 3 times a one-point solve).

The per-run overhead the issue bounds (10 ms beyond the run's own time) is measured apart, on the
same sweep run by a Runner in this process: its run phase (no start-up, no report), less the
truths' time (one per sweep point, timed apart) and the work, over the rows. On a shared machine
that wall time mostly measures the other processes (a run waits for a core before and after each
hand-over between this process and its worker), so the same overhead is also given in CPU time:
this process's CPU less the truths', plus the worker children's CPU less what they spent inside
the timed runs (build, warm-up and repeats), over the rows: what the harness itself computes.

The native + MuJoCo sweep of the issue's target, serial and on a local Dask cluster:

    python -m benchmarks.run_overhead --engines reference,mujoco --points 200 --workers 2 --scenarios 0
"""

from __future__ import annotations

import argparse
import multiprocessing
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import pandas as pd

from reports.run import group_runs
from reports.run.runner import RunConfig, Runner
from reports.run.sweep import points
from reports.scoring.truth import NamedTruth, independent_truth
from reports.store.results_store import ResultsStore, read_results
from reports.suites import Suite, main_scenarios
from reports.suites import get as suite_named
from scenarios import Scenario, Trajectory


def wall(arguments: list[str]) -> float:
    """Seconds for `mbxval ARGUMENTS` in a fresh interpreter (its output dropped, its failure raised)."""
    start = time.perf_counter()
    subprocess.run([sys.executable, "-m", "mbxval", *arguments], check=True, capture_output=True)
    return time.perf_counter() - start


WORK = ("build_time_wall", "warmup_time_wall", "repeats_time_wall")
"""The measured parts of a row's work: its build, its untimed warm-up and its timed repeats, on the
wall clock like the run phase they are taken from (a row's CPU seconds count every thread of its
process, and can exceed the wall time they passed in)."""


def work(rows: pd.DataFrame) -> float:
    """Seconds of work the rows measured: the sum of their WORK columns (a failed run times
    nothing: its parts are NaN, counted as 0)."""
    return float(sum(rows[column].fillna(0).sum() for column in WORK))


def work_of(out: Path) -> tuple[int, float, float]:
    """Rows, compute and work of a results store (see the module's docstring)."""
    rows, _ = read_results(out)
    compute = float((rows["build_time"].fillna(0) + rows["run_time"].fillna(0)).sum())
    return len(rows), compute, work(rows)


def run_phase(label: str, names: list[str], engines: list[str], suite: Suite, out: Path) -> None:
    """The per-run overhead of the run phase, in this process: wall - truths - work, per row; and
    in CPU time (see the module's docstring)."""
    spent, spent_cpu = [0.0], [0.0]
    truth = suite.truth or independent_truth

    def timed_truth(scenario: Scenario, times: np.ndarray) -> Trajectory | NamedTruth:
        start, cpu = time.perf_counter(), time.process_time()
        try:
            return truth(scenario, times)
        finally:
            spent[0] += time.perf_counter() - start
            spent_cpu[0] += time.process_time() - cpu

    config = RunConfig(suite.ladder, suite.repeats, suite.warmup, suite.timeout)
    store = ResultsStore(out)
    runner = Runner(store, engines, config, truth=timed_truth, progress=False, settings=suite.settings)
    timed_cpu = multiprocessing.get_context("fork").Value("d", 0.0)  # shared with the forked workers
    timed_run = group_runs.timed_run

    def cpu_timed_run(*arguments: object, **keywords: object) -> object:
        cpu = time.process_time()
        try:
            return timed_run(*arguments, **keywords)  # type: ignore[arg-type]
        finally:
            with timed_cpu.get_lock():
                timed_cpu.value += time.process_time() - cpu

    group_runs.timed_run = cpu_timed_run  # type: ignore[assignment]
    children_before = _children_cpu()
    start, cpu = time.perf_counter(), time.process_time()
    try:
        runner.run(names)
    finally:
        group_runs.timed_run = timed_run
    seconds, parent_cpu = time.perf_counter() - start, time.process_time() - cpu
    for child in multiprocessing.active_children():  # the released workers: reaped, their CPU counted
        child.join(10.0)
    children_cpu = _children_cpu() - children_before
    count, _, done = work_of(out)
    rows = max(count, 1)
    per_run = (seconds - spent[0] - done) / rows
    parent_part = (parent_cpu - spent_cpu[0]) / rows
    child_part = (children_cpu - timed_cpu.value) / rows
    print(
        f"{label}, run phase in-process: {count} rows in {seconds:.2f} s, of which truths "
        f"{spent[0]:.2f} s ({1000 * spent[0] / max(len(names), 1):.0f} ms per scenario) "
        f"and work {done:.3f} s; "
        f"overhead {1000 * per_run:.1f} ms per run (target: at most 10); in CPU time "
        f"{1000 * (parent_part + child_part):.1f} ms per run (this process {1000 * parent_part:.1f}, "
        f"workers {1000 * child_part:.1f}); load {_load()}"
    )


def _children_cpu() -> float:
    """CPU seconds of this process's reaped children."""
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def _load() -> str:
    """The 1-minute load average (other processes share the cores)."""
    with open("/proc/loadavg") as loadavg:
        return loadavg.read().split()[0]


def measure(label: str, arguments: list[str], out: Path) -> dict[str, float]:
    seconds = wall(["run", *arguments, "--out", str(out), "--quiet"])
    count, compute, done = work_of(out)
    per_run = (seconds - done) / max(count, 1)
    print(
        f"{label:<28} {count:5d} {seconds:8.2f} {compute:9.3f} {done:8.3f} "
        f"{seconds / compute:9.1f} {seconds / done:8.1f} {1000 * per_run:10.1f}"
    )
    return {"wall": seconds, "work": done}


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(prog="run_overhead", description=__doc__.splitlines()[0])
    parser.add_argument("--scenario", default="four_bar", help="scenario of the sweep (default four_bar)")
    parser.add_argument("--points", type=int, default=16, help="sweep points, omega 10 to 40 (default 16)")
    parser.add_argument("--engines", default="reference", help="engines of the sweep (default reference)")
    parser.add_argument("--sweep", action="append", help="sweep specs instead of omega=lin:10:40:POINTS")
    parser.add_argument("--suite", help="the sweep's suite options (quick: default settings, timed once)")
    parser.add_argument("--workers", type=int, help="run the sweep on a local Dask cluster of N workers too")
    parser.add_argument("--scenarios", type=int, default=6, help="default-suite scenarios (default 6)")
    parser.add_argument("--suite-engines", default="reference,mujoco", help="engines of the suite subset")
    args = parser.parse_args(argv)
    if not 1 <= args.points <= 1000 or not 0 <= args.scenarios <= 1000:
        parser.error("--points must be in [1, 1000] and --scenarios in [0, 1000]")
    engines = [a for e in args.engines.split(",") for a in ("--engine", e)]
    suite_engines = [a for e in args.suite_engines.split(",") for a in ("--engine", e)]
    print(f"{'case':<28} {'rows':>5} {'wall s':>8} {'compute s':>9} {'work s':>8} "
          f"{'wall/comp':>9} {'wall/work':>8} {'ms/run over':>10}")  # fmt: skip
    with tempfile.TemporaryDirectory(prefix="mbxval-overhead-") as temporary:
        base = Path(temporary)
        sweeps = [a for spec in args.sweep or [f"omega=lin:10:40:{args.points}"] for a in ("--sweep", spec)]
        chosen = [
            "--scenario",
            args.scenario,
            *engines,
            *sweeps,
            *(["--suite", args.suite] if args.suite else []),
        ]
        native = measure(f"sweep {args.scenario} serial", chosen, base / "sweep")
        if args.workers:
            workers = ["--workers", str(args.workers)]
            parallel = measure(f"sweep --workers {args.workers}", [*chosen, *workers], base / "dask")
            print(f"--workers {args.workers} against serial: {native['wall'] / parallel['wall']:.2f}x faster")
        if args.scenarios:
            names = main_scenarios()[: args.scenarios]
            chosen = [a for n in names for a in ("--scenario", n)]
            measure(f"default suite, {len(names)} scen.", [*chosen, *suite_engines], base / "suite")
        solve = wall(["solve", args.scenario, "--out", str(base / "solve.csv")])
        print(f"one-point solve of {args.scenario}: {solve:.2f} s wall")
        print(f"sweep wall / one-point solve wall: {native['wall'] / solve:.1f}x (target: at most 3x)")
        specs = args.sweep or [f"omega=lin:10:40:{args.points}"]
        swept = points([args.scenario], specs)
        suite = suite_named(args.suite or "default")
        run_phase("sweep", swept, args.engines.split(","), suite, base / "in-process")
        if args.scenarios:
            engines = args.suite_engines.split(",")
            run_phase("default suite", names, engines, suite_named("default"), base / "suite-in-process")


if __name__ == "__main__":
    main()
