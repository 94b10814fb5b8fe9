"""What a save of the results store costs: appending a batch of rows to stores of 1k, 10k and 100k
rows, the whole table rewritten at every save beside the store's way (the batch written as a new
part), measured side by side in one run.

    python -m benchmarks.store_append [--sizes 1000,10000,100000] [--batch 100] [--appends 8]
        [--grow 10000]

Rows are the store's declared columns (reports.store.columns) with values of a sweep's rows
(scenario names with parameters, engines, settings, options as JSON, errors, timings, provenance).
For each size the store is first saved whole once; then `appends` batches of `batch` new rows are
saved one after another, each timed from the call to `save` to its return (the new part written,
synced, checksummed; the sidecar; the generation switched), compaction included: best, median and
worst. The whole rewrite (`old_save`, kept here only to compare) is a store of one file per table: the
table built from every row, written whole as one file, checksummed, committed. Beside them, the cost of
a load (read_results: every part read and its SHA-256 verified) and of the verification alone.
`--grow N` then builds a store of N rows by batches of `batch`, as a sweep does, both ways: the
total and the slowest save (the new way's slowest is a save that merges parts).
"""

from __future__ import annotations

import argparse
import json
import math
import random
import statistics
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pandas as pd

from reports.store import files as store_files
from reports.store.columns import DECLARED
from reports.store.layout import read_sidecar, verify
from reports.store.results_store import RESULTS, TRAJECTORIES, ResultsStore, key_of, read_results, rows_frame

ENGINES = {
    "reference": ("native", ["newton tol=1e-10", "newton tol=1e-12", "fast tol=1e-10"]),
    "mujoco": ("implicitfast", ["implicitfast dt=0.001", "implicitfast dt=0.0001", "rk4 dt=0.001"]),
    "exudyn": ("static", ["static", "generalized_alpha dt=0.001", "trapezoidal dt=0.001"]),
    "pinocchio": ("kinematic", ["kinematic tol=1e-10", "aba dt=0.001"]),
}
META = {"suite": "bench", "machine": "bench", "truth": "closed form", "headline": "", "scales": ""}


def realistic_rows(count: int, start: int = 0, seed: int = 0) -> list[dict[str, Any]]:
    """`count` rows of a sweep (four_bar over omega, every engine and setting), all declared
    columns filled as a run fills them; row keys numbered from `start`, so batches do not collide."""
    generator = random.Random(seed + start)
    rows = []
    labels = [(e, mode, s) for e, (mode, settings) in ENGINES.items() for s in settings]
    for index in range(start, start + count):
        point, (engine, mode, setting) = divmod(index, len(labels))[0], labels[index % len(labels)]
        omega = 10 + point * 1e-3
        row: dict[str, Any] = {}
        for column in DECLARED:
            if isinstance(column.empty, bool):
                row[column.name] = generator.random() < 0.5
            elif isinstance(column.empty, int):
                row[column.name] = generator.randrange(1, 20000)
            elif isinstance(column.empty, float):
                row[column.name] = 10 ** generator.uniform(-14, -2)
            else:
                row[column.name] = ""
        row.update(
            scenario=f"four_bar[omega={omega:.4f}]",
            family="four_bar",
            variant="crank_rocker",
            sweep=json.dumps({"omega": omega}),
            scenario_digest=f"{generator.getrandbits(64):016x}",
            engine=engine,
            engine_version="3.2.7",
            mode=mode,
            measures="the engine's own integrator",
            setting=setting,
            options=json.dumps({"dt": 0.001} if "dt=" in setting else {"tol": 1e-10}),
            status="ok" if generator.random() < 0.95 else "diverged",
            message="",
            warnings="",
            levels="position,velocity,acceleration",
            truth="closed form",
            self_check="",
            host="bench-host",
            recorded_at="2026-11-25T07:00:00Z",
            revision=f"{generator.getrandbits(160):040x}",
            failure_time=math.nan,
        )
        rows.append(row)
    return rows


def old_save(directory: Path, rows: dict[Any, dict[str, Any]]) -> None:
    """A save that rewrites the whole table (for comparison only): every row into one table,
    written whole as results.parquet in a new generation (no trajectories here)."""
    frame = rows_frame(rows.values())
    writers: dict[str, Callable[[Path], object]] = {
        RESULTS: lambda path: frame.to_parquet(path, index=False),
        TRAJECTORIES: lambda path: pd.DataFrame(columns=["scenario", "engine", "setting"]).to_parquet(
            path, index=False
        ),
    }
    store_files.commit(directory, writers, META)


def timed(action: Callable[[], object]) -> float:
    start = time.perf_counter()
    action()
    return time.perf_counter() - start


def appends(size: int, batch: int, count: int, folder: Path) -> tuple[list[float], list[float]]:
    """Seconds of `count` saves of `batch` new rows each onto a store of `size` rows: old, new."""
    base = realistic_rows(size)
    old_rows = {key_of(r): r for r in base}
    old_dir, new_dir = folder / f"old-{size}", folder / f"new-{size}"
    old_save(old_dir, old_rows)
    store = ResultsStore(new_dir)
    store.rows = old_rows
    store.save(dict(META))
    old, new = [], []
    for k in range(count):
        more = realistic_rows(batch, start=size + k * batch)
        for row in more:
            old_rows[key_of(row)] = row
        old.append(timed(lambda: old_save(old_dir, old_rows)))
        for row in more:
            store.add(row)
        new.append(timed(lambda: store.save(dict(META))))
    return old, new


def load_costs(directory: Path) -> tuple[float, float]:
    """Seconds of a load (read_results, verified) and of the SHA-256 verification alone."""
    generation = store_files.committed(directory)
    assert generation is not None
    meta = read_sidecar(generation, directory)
    return timed(lambda: read_results(directory)), timed(lambda: verify(generation, directory, meta))


def grow(total: int, batch: int, folder: Path) -> tuple[list[float], list[float]]:
    """Seconds of each save building a store of `total` rows by `batch` rows (a sweep): old, new."""
    old_rows: dict[Any, dict[str, Any]] = {}
    store = ResultsStore(folder / "grow-new")
    old, new = [], []
    for start in range(0, total, batch):
        rows = realistic_rows(min(batch, total - start), start=start)
        old_rows.update({key_of(r): r for r in rows})
        old.append(timed(lambda: old_save(folder / "grow-old", old_rows)))
        for row in rows:
            store.add(row)
        new.append(timed(lambda: store.save(dict(META))))
    return old, new


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(prog="store_append", description=__doc__.splitlines()[0])
    parser.add_argument(
        "--sizes", default="1000,10000,100000", help="store sizes in rows (default 1k,10k,100k)"
    )
    parser.add_argument("--batch", type=int, default=100, help="rows per save (default 100)")
    parser.add_argument("--appends", type=int, default=8, help="saves timed per size (default 8)")
    parser.add_argument("--grow", type=int, default=10000, help="rows of the sweep built both ways (0: none)")
    args = parser.parse_args(argv)
    sizes = [int(s) for s in args.sizes.split(",") if s]
    print(f"appending {args.batch} rows to a store, {args.appends} saves each; seconds per save")
    print(
        f"{'rows':>8} {'old best':>9} {'old med':>8} {'new best':>9} {'new med':>8} {'new worst':>9} "
        f"{'old/new':>8} {'load':>7} {'sha256':>7}"
    )
    with tempfile.TemporaryDirectory(prefix="mbxval-bench-store-") as temporary:
        folder = Path(temporary)
        for size in sizes:
            old, new = appends(size, args.batch, args.appends, folder)
            load, digest = load_costs(folder / f"new-{size}")
            ratio = statistics.median(old) / statistics.median(new)
            print(
                f"{size:8d} {min(old):9.3f} {statistics.median(old):8.3f} {min(new):9.3f} "
                f"{statistics.median(new):8.3f} {max(new):9.3f} {ratio:8.1f} {load:7.3f} {digest:7.3f}"
            )
        if args.grow:
            old, new = grow(args.grow, args.batch, folder)
            saves = math.ceil(args.grow / args.batch)
            print(
                f"a sweep of {args.grow} rows saved every {args.batch} ({saves} saves): "
                f"old {sum(old):.2f} s, new {sum(new):.2f} s, ratio {sum(old) / sum(new):.1f}; "
                f"slowest save: old {max(old):.3f} s, new {max(new):.3f} s (a merge of parts)"
            )


if __name__ == "__main__":
    main()
