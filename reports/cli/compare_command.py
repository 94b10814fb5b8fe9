"""`mbxval compare SCENARIO TRAJECTORY.csv`: score a trajectory made by any tool against the truth,
print a one-screen verdict per level, and with --out add it to a results store beside the engines.

Everything the user gives is checked before anything is written: the scenario, the file (its
columns, grid and values: reports.run.trajectory_file), the label, and that the store holds no
other mechanism under the scenario's name.
"""

from __future__ import annotations

import argparse
import math
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

import adapters
from reports.cli.usage import UsageError, pairs, scenario_argument
from reports.scoring import LEVEL_COLUMNS, characteristic_rate
from reports.store import WriterLock, committed, scenario_identity
from scenarios import Scenario, limits, load
from scenarios.names import NameRefused, safe_file_stem
from scenarios.scenario import LEVELS

if TYPE_CHECKING:  # the store, the scoring and the report's scale are imported when a comparison runs
    from reports.run import Score
    from reports.store import ResultsStore

SCALE_WORDS = ("green", "yellow", "red")


def colour_word(error: float) -> str:
    """Where `error` falls on the report's colour scale: green up to 10^(BEST + a third of the
    span), red from two thirds on (the report colours by log error; it has no pass/fail line)."""
    from reports.render import BEST, WORST

    if math.isinf(error):
        return SCALE_WORDS[-1]
    share = (math.log10(max(error, 1e-300)) - BEST) / (WORST - BEST)
    return SCALE_WORDS[min(max(int(share * 3), 0), 2)]


def check_label(label: object, what: str = "--label") -> str:
    """A label that cannot be mistaken for an engine's rows or the truth's, and is a name that may
    become a file name (scenarios.names.safe_file_stem: a path, blank, over-long or control
    characters are refused)."""
    from reports.store import TRUTH

    try:
        label = safe_file_stem(label, what)
    except NameRefused as refused:
        raise UsageError(str(refused)) from None
    if label in adapters.names() or label == TRUTH:
        raise UsageError(f"--label '{label}' is the name of an engine or of the truth; choose another")
    return label


def verdict(scenario: Scenario, scored: Score, label: str) -> list[str]:
    """The lines of the one-screen verdict."""
    from reports.render import BEST, WORST

    row, imported = scored.row, scored.imported
    lines = [
        f"{label}: {imported.source} against {scenario.name} ({len(imported.trajectory.times)} times, "
        f"bodies {', '.join(imported.trajectory.bodies)})",
        f"truth: {scored.truth.name}",
        f"scales: lengths / L = {scenario.characteristic_length:g} m, rates / w = "
        f"{characteristic_rate(scenario):.6g} rad/s (errors are dimensionless, the largest over the grid)",
        "",
        f"{'level':<14}{'error':>10}   report colour (log scale, 1e{BEST:.0f} green to 1e{WORST:.0f} red)",
    ]
    for level in LEVELS:
        if level not in scenario.levels:
            lines.append(f"{level:<14}{'-':>10}   not asked for by {scenario.name}")
        elif level in imported.missing_levels:
            lines.append(f"{level:<14}{'-':>10}   not in the file")
        else:
            error = scored.level_error(level)
            word = "not compared" if math.isnan(error) else colour_word(error)
            lines.append(f"{level:<14}{error:>10.2e}   {word}")
    residual = float(row.get("constraint_residual", math.nan))
    if math.isfinite(residual):
        lines.append(f"{'residual':<14}{residual:>10.2e}   largest scaled constraint residual |C|")
    if row.get("message"):
        lines += ["", f"note: {row['message']}"]
    return lines


def cmd_compare(args: argparse.Namespace) -> int:
    from reports.run import TrajectoryFileError, add_to_store, read_trajectory, score
    from reports.store import ResultsStore

    scenario = load(args.scenario, pairs(args.set, "--set"))
    if args.label is not None:
        label = check_label(args.label)
    else:
        label = check_label(
            Path(args.trajectory).stem, "the label (the file's stem unless --label gives one)"
        )
    limits.check_dense_rows(scenario.name, len(scenario.bodies))  # the truth's forces: before reading
    try:
        imported = read_trajectory(args.trajectory, scenario)
    except TrajectoryFileError as error:
        raise UsageError(str(error)) from None
    bodies, points = len(scenario.bodies), imported.trajectory.times.size
    limits.check_grid(scenario.name, points, bodies, dense=True)  # the truth's forces are dense
    out = Path(args.out) if args.out is not None else None
    if out is not None:
        if out.exists() and not out.is_dir():
            raise UsageError(f"--out {out} is a file, not a directory")
        _check_store(out, args.scenario, scenario)
    scored = score(scenario, imported, label)
    print("\n".join(verdict(scenario, scored, label)))
    if out is not None:
        with WriterLock(out, wait=args.wait):
            store = ResultsStore(out)
            add_to_store(store, scenario, scored)
        print("\n".join(["", *beside(store, scenario.name)]))
        print(f"added to {out} as engine '{label}'; see it beside the engines: mbxval report {out}")
    return 0


def beside(store: ResultsStore, name: str) -> list[str]:
    """The store's default-setting rows of scenario `name`, one line each: engine, status, errors."""
    lines = [f"{'in the store':<14}{'position':>10}{'velocity':>10}{'accel.':>10}   setting"]
    rows = [r for r in store.rows.values() if r["scenario"] == name and bool(r["is_default"])]
    for row in sorted(rows, key=lambda r: str(r["engine"])):
        if row["status"] != "ok":
            lines.append(f"{row['engine']!s:<14}{row['status']!s:>10}")
            continue
        values = "".join(f"{float(row[LEVEL_COLUMNS[lv]]):>10.1e}" for lv in LEVELS)
        lines.append(f"{row['engine']!s:<14}{values}   {row['setting']}")
    return lines


def _check_store(out: Path, given: str, scenario: Scenario) -> None:
    """Refuse a store that holds another mechanism under the scenario's name (a family's rows and a
    file of its name, in either order: reports.store.scenario_identity)."""
    from reports.store import ResultsStore

    if committed(out) is None:
        return
    rows = ResultsStore(out).rows.values()
    clash = scenario_identity.stored_clash(rows, given, scenario, str(out))
    if clash is not None:
        raise UsageError(clash)


def add_parser(sub: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    """Add `compare` to the command line."""
    compare = sub.add_parser("compare", help="score a trajectory CSV from any tool against the truth")
    scenario_argument(compare)
    compare.add_argument("trajectory", help="trajectory CSV: t, then BODY.x BODY.y BODY.theta BODY.vx ...")
    compare.add_argument("--label", help="its name in results and the report (default: the file's stem)")
    compare.add_argument("--out", help="results directory to add the row to (made if it does not exist)")
    compare.add_argument("--wait", action="store_true", help="wait for another run writing --out to end")


COMMANDS: dict[str, Callable[[argparse.Namespace], int]] = {"compare": cmd_compare}
