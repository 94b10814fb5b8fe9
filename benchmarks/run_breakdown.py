"""Where a run phase goes: a Runner's run of a selection in this process, each step the harness takes
around the work it measures timed, in this process and in the workers' children.

    python -m benchmarks.run_breakdown [--scenario NAME ...] [--engine NAME ...]
        [--sweep NAME=SPEC ...] [--suite quick]

The work is what the rows measured (build, warm-up and timed repeats: benchmarks.run_overhead.work);
the overhead is the run phase's wall time less the work, and the table splits it (seconds, and
milliseconds per row):
- set-up: the engines loaded and the provenance read (Runner()), the runs planned;
- truths (one per scenario), warming a scenario before a fork, forks;
- hand-over: a worker's call less the child's time in it (pipes, pickling, waiting for a core);
- in the child: the adapter's run beyond the work it measured, the constraint residual (cam
  scenarios apart, each part with its milliseconds per run of its own) and the rest of the
  comparison (errors per level, forces);
- in this process: the rows made, the store's add, the progress bar, the saves;
- unaccounted: what is left (the loop itself, resume bookkeeping).
On a shared machine the wall time of a step mostly measures the other processes: the CPU seconds
of this process's steps and of the children's calls are printed beside, with the load.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import math
import os
import tempfile
import time
from collections import defaultdict
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

from benchmarks.run_overhead import work
from reports.run import group_runs, isolation, runner
from reports.run.runner import Runner
from reports.run.sweep import points
from reports.scoring import comparison
from reports.store.results_store import ResultsStore, read_results
from reports.suites import get as suite_named

PARENT_STEPS = (
    (runner.Runner, "_plan", "planning"),
    (runner, "solve_truth", "truths"),
    (group_runs, "warm", "warming before a fork"),
    (isolation.Worker, "_start", "forks"),
    (isolation.Worker, "call", "calls"),
    (group_runs, "_stored", "rows"),
    (runner.Runner, "_add", "store add"),
    (runner, "tick", "progress bar"),
    (runner.Runner, "_save", "saves"),
)
CHILD_STEPS = ((group_runs, "timed_run"), (group_runs, "measure"), (comparison, "residual_metrics"))


class Clock:
    """Seconds (wall and CPU) and calls per step, summed."""

    def __init__(self) -> None:
        self.wall: dict[str, float] = defaultdict(float)
        self.cpu: dict[str, float] = defaultdict(float)
        self.calls: dict[str, int] = defaultdict(int)

    def timing(self, step: str, function: Callable[..., Any]) -> Callable[..., Any]:
        def timed(*arguments: Any, **keywords: Any) -> Any:
            start, cpu = time.perf_counter(), time.process_time()
            try:
                return function(*arguments, **keywords)
            finally:
                self.wall[step] += time.perf_counter() - start
                self.cpu[step] += time.process_time() - cpu
                self.calls[step] += 1

        return timed


@contextlib.contextmanager
def timed_steps(clock: Clock, log: Path) -> Iterator[None]:
    """The harness with its steps timed: this process's into `clock`, each child's call (one JSON
    line per run: its steps, its work, its scenario) appended to `log`; restored on leaving."""
    saved = [(owner, name, getattr(owner, name)) for owner, name, _ in PARENT_STEPS]
    saved += [(owner, name, getattr(owner, name)) for owner, name in CHILD_STEPS]
    saved.append((group_runs, "_measure", group_runs._measure))
    for owner, name, step in PARENT_STEPS:
        setattr(owner, name, clock.timing(step, getattr(owner, name)))
    child = Clock()  # the child's copy counts its own call (forked: each child has its own)
    for owner, name in CHILD_STEPS:
        setattr(owner, name, child.timing(name, getattr(owner, name)))
    measure = group_runs._measure

    def logged(*arguments: Any) -> Any:
        for table in (child.wall, child.cpu):
            table.clear()
        start, cpu = time.perf_counter(), time.process_time()
        value = measure(*arguments)
        result, held = value[0], arguments[3]
        record = {
            "scenario": held["group"][0].name,
            "total": time.perf_counter() - start,
            "cpu": time.process_time() - cpu,
            "work": sum(
                _seconds(x)
                for x in (result.build_time_wall, result.warmup_time_wall, result.repeats_time_wall)
            ),
            "wall": dict(child.wall),
        }
        with open(log, "a") as out:
            out.write(json.dumps(record) + "\n")
        return value

    setattr(group_runs, "_measure", logged)  # noqa: B010 (the harness's own signature, logged)
    try:
        yield
    finally:
        for owner, name, original in saved:
            setattr(owner, name, original)


def breakdown(names: list[str], engines: list[str], suite_name: str, out: Path) -> dict[str, Any]:
    """Run `names` on `engines` with `suite_name`'s configuration into a new store in `out`, timed
    step by step; the table's lines (label, seconds) and the totals."""
    suite = suite_named(suite_name)
    config = group_runs.RunConfig(suite.ladder, suite.repeats, suite.warmup, suite.timeout)
    clock, log = Clock(), out / "children.jsonl"
    load = _load()
    with timed_steps(clock, log):
        start, times = time.perf_counter(), os.times()
        store = ResultsStore(out / "store")
        made = Runner(store, engines, config, truth=suite.truth, progress=True, settings=suite.settings)
        set_up = time.perf_counter() - start
        made.run(names)
        wall, after = time.perf_counter() - start, os.times()
    rows, _ = read_results(out / "store")
    done = work(rows)
    children = [json.loads(line) for line in log.read_text().splitlines()] if log.exists() else []
    in_child = sum(c["total"] for c in children)
    timed = sum(c["wall"].get("timed_run", 0.0) for c in children)
    compare = sum(c["wall"].get("measure", 0.0) for c in children)
    residual = sum(c["wall"].get("residual_metrics", 0.0) for c in children)
    cam_runs = [c for c in children if c["scenario"].startswith("cam")]
    cams = sum(c["wall"].get("residual_metrics", 0.0) for c in cam_runs)
    lines = [
        ("set-up (engines, provenance)", set_up),
        ("planning", clock.wall["planning"]),
        (f"truths ({clock.calls['truths']})", clock.wall["truths"]),
        ("warming before a fork", clock.wall["warming before a fork"]),
        (f"forks ({clock.calls['forks']})", clock.wall["forks"]),
        ("hand-over (call - child)", clock.wall["calls"] - clock.wall["forks"] - in_child),
        ("child: adapter run beyond work", timed - sum(c["work"] for c in children)),
        (f"child: residual, cams {_per_run(cams, len(cam_runs))}", cams),
        (
            f"child: residual, others {_per_run(residual - cams, len(children) - len(cam_runs))}",
            residual - cams,
        ),
        ("child: rest of the comparison", compare - residual),
        ("child: the rest of the call", in_child - timed - compare),
        ("rows", clock.wall["rows"]),
        ("store add", clock.wall["store add"]),
        ("progress bar", clock.wall["progress bar"]),
        (f"saves ({clock.calls['saves']} due or not)", clock.wall["saves"]),
    ]
    unaccounted = wall - done - sum(seconds for _, seconds in lines)
    return {
        "rows": len(rows),
        "wall": wall,
        "work": done,
        "lines": [*lines, ("unaccounted", unaccounted)],
        "cpu": (after.user + after.system - times.user - times.system, sum(c["cpu"] for c in children)),
        "cpu_steps": dict(clock.cpu),
        "load": f"{load} -> {_load()}",
    }


def table(found: dict[str, Any]) -> str:
    rows = max(found["rows"], 1)
    over = found["wall"] - found["work"]
    head = (
        f"{found['rows']} rows: run phase {found['wall']:.2f} s, work {found['work']:.2f} s, overhead "
        f"{over:.2f} s = {1000 * over / rows:.1f} ms per row (load {found['load']})"
    )
    body = [
        f"  {label:<50} {seconds:8.3f} s {1000 * seconds / rows:8.2f} ms/row"
        for label, seconds in found["lines"]
    ]
    parent, children = found["cpu"]
    steps = ", ".join(f"{step} {seconds:.3f}" for step, seconds in found["cpu_steps"].items())
    tail = f"CPU s: this process {parent:.2f} ({steps}); children's calls {children:.2f}"
    return "\n".join([head, *body, tail])


def _per_run(seconds: float, runs: int) -> str:
    """`(N runs, M ms a run)`: a step that only some runs take, over those runs."""
    return f"({runs} runs, {1000 * seconds / max(runs, 1):.2f} ms a run)"


def _seconds(value: float | None) -> float:
    """A measured time, 0 where none was measured (None or NaN: a failed run times nothing)."""
    return 0.0 if value is None or math.isnan(value) else value


def _load() -> str:
    with open("/proc/loadavg") as loadavg:
        return loadavg.read().split()[0]


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(prog="run_breakdown", description=__doc__.splitlines()[0])
    parser.add_argument("--scenario", action="append", help="scenario (default four_bar and cam_roller)")
    parser.add_argument("--engine", action="append", help="engine (default reference and mujoco)")
    parser.add_argument("--sweep", action="append", help="sweep specs over the first scenario")
    parser.add_argument("--suite", default="default", help="the suite whose configuration to run")
    args = parser.parse_args(argv)
    names = args.scenario or ["four_bar", "cam_roller"]
    if args.sweep:
        names = points(names[:1], args.sweep)
    with tempfile.TemporaryDirectory(prefix="mbxval-breakdown-") as temporary:
        found = breakdown(names, args.engine or ["reference", "mujoco"], args.suite, Path(temporary))
    print(table(found))


if __name__ == "__main__":
    main()
