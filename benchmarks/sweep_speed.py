"""Wall time of a parameter sweep run serially and on a local Dask cluster, and the speed-up.

    python -m benchmarks.sweep_speed [--workers 2] [--engines reference,mujoco] [--out DIR]

The sweep: the four-bar over 50 crank speeds (log-spaced, 10 to 1e4 rad/s) and 4 crank lengths
(0.05 to 0.2 m: from 0.08 m on the linkage meets a dead point, where the native solver stops), 200
points, each engine at its default setting timed once without warm-up (the quick suite's configuration).
Both runs start from an empty store and include everything the runner does (truths, forked runs,
saving the store after each group); the Dask run includes starting the cluster. Beside each wall
time, the work its rows measured (build, warm-up and timed repeats, benchmarks.run_overhead.work)
and the ratio the issue bounds (serial wall at most 1.5 times the work), and the failed rows' share
of the work (a run that stops at the dead point records what it spent). With --out, the Dask
run's results and report (with the swept stability map) are kept there.
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

from benchmarks.run_overhead import work
from reports.run.dask_backend import DaskRunner
from reports.run.runner import RunConfig, Runner
from reports.run.sweep import points
from reports.store.results_store import ResultsStore, read_results

SWEEP = ("omega=log:10:1e4:50", "crank_length=lin:0.05:0.2:4")
CONFIG = RunConfig(ladder=False, repeats=1, warmup=0)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(prog="sweep_speed", description=__doc__.splitlines()[0])
    parser.add_argument("--workers", type=int, default=2, help="Dask worker processes (default 2)")
    parser.add_argument("--engines", default="reference,mujoco", help="comma-separated engines")
    parser.add_argument("--scenario", default="four_bar", help="scenario to sweep (default four_bar)")
    parser.add_argument("--sweep", action="append", help=f"sweep specs (default {' '.join(SWEEP)})")
    parser.add_argument("--out", help="keep the Dask run's results and report here")
    args = parser.parse_args(argv)
    engines = args.engines.split(",")
    names = points([args.scenario], args.sweep or SWEEP)
    print(f"{len(names)} points x {len(engines)} engines ({', '.join(engines)}), {args.workers} workers")
    with tempfile.TemporaryDirectory(prefix="mbxval-sweep-") as temporary:
        start = time.perf_counter()
        Runner(ResultsStore(Path(temporary) / "serial"), engines, CONFIG, progress=False).run(names)
        serial = time.perf_counter() - start
        print(timing_line("serial:", serial, Path(temporary) / "serial"))
        out = Path(args.out) if args.out else Path(temporary) / "dask"
        start = time.perf_counter()
        runner = DaskRunner(ResultsStore(out), engines, CONFIG, progress=False, workers=args.workers)
        runner.run(names)
        parallel = time.perf_counter() - start
        print(timing_line(f"--workers {args.workers}:", parallel, out))
    print(f"speed-up:         {serial / parallel:8.2f}x")
    if args.out:
        from reports.render.report import render_reports

        print(f"report: {render_reports(out)}")


def timing_line(label: str, wall: float, out: Path) -> str:
    """A run's wall time beside the work its stored rows measured, and their ratio."""
    rows, _ = read_results(out)
    done = work(rows)
    ratio = f"{wall / done:.2f}" if done > 0 else "-"
    failed = rows[rows["status"] != "ok"]
    return (
        f"{label:<17} {wall:8.1f} s wall, {done:8.2f} s work ({len(rows)} rows), wall/work {ratio}"
        f" [failed rows: {len(failed)}, {work(failed):.2f} s of the work]"
    )


if __name__ == "__main__":
    main()
