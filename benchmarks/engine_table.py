"""Every engine's accuracy on the issue's scenes, untuned, by the settings rule and at its best, and
the four-bar's verdict against the number of outputs: the page docs/engine-accuracy.md, generated.

    nice -n 10 python -m benchmarks.engine_table [--out DIR] [--page docs/engine-accuracy.md]

The cells are made by the harness's own Runner, as `mbxval run` makes them (each engine's ladder,
its run-in, the harness truth, the force truth), into a results store under DIR (a temporary one by
default), and read back from the stored rows alone:
- untuned: the row stored with `is_untuned` (the engine's own defaults at the rule's step);
- default: the row stored with `is_default`;
- best: the rung with the smallest worst error over position, velocity and acceleration (the
  report's reading, reports.render.engine_reach), with its setting.
Each cell gives the errors at P / V / A / force (relative, as the report measures them) and the CPU
µs per engine step (run time over the row's steps: per output time where the engine has no step).
A force an engine does not give is a dash, with the reason its row names (or `none named` where the
row is silent). The four-bar's verdicts are the defaults at 20, 200 and 2000 outputs over the turn.
The page's text between BEGIN and END is replaced; the rest of it is left as written.
"""

from __future__ import annotations

import argparse
import math
import re
import tempfile
from pathlib import Path

import pandas as pd

from reports.run.runner import RunConfig, Runner
from reports.store.columns import LEVEL_COLUMNS
from reports.store.results_store import ResultsStore, read_results

SCENARIOS = (
    "slider_crank",
    "four_bar",
    "four_bar_gravity",
    "andrews_squeezer",
    "cam_roller",
    "cam_roller/spline",
    "spur_gears",
)
ENGINES = ("mujoco", "exudyn", "pinocchio", "reference")
OUTPUTS = (20, 200, 2000)
"""The four-bar's output counts over its turn for the verdict's dependence on the grid."""
LEVELS = (*LEVEL_COLUMNS.values(), "error_force")
MOTION = list(LEVEL_COLUMNS.values())
BEGIN, END = "<!-- BEGIN engine_table -->", "<!-- END engine_table -->"
PAGE = Path("docs/engine-accuracy.md")
FORCE_REASON = re.compile(r"forces not given[^|]*|forces not compared[^;|]*")


def run_cells(out: Path, names: list[str], ladder: bool) -> pd.DataFrame:
    """The stored rows of `names` on every engine (each one's ladder when `ladder`), one timed run
    each without a warm-up (frugal: the build is timed apart from the run)."""
    config = RunConfig(ladder=ladder, repeats=1, warmup=0, timeout=300.0)
    Runner(ResultsStore(out), ENGINES, config, progress=False).run(names)
    rows, _ = read_results(out)
    return rows[rows["scenario"].isin(names)]


def _e(value: float) -> str:
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "–"
    return "0" if value == 0 else f"{value:.1e}"


def _force_reason(row: pd.Series) -> str:
    found = FORCE_REASON.search(f"{row.get('warnings', '')} | {row.get('message', '')}")
    return found.group(0).strip().rstrip(".") if found else "none named"


def forceless(chosen: dict[str, pd.Series | None]) -> str:
    """Which of the chosen rows give no forces, and the reason each names."""
    found: dict[str, list[str]] = {}
    for which, row in chosen.items():
        if row is not None and row["status"] == "ok" and math.isnan(float(row["error_force"])):
            found.setdefault(_force_reason(row), []).append(which)
    return "; ".join(f"{', '.join(whiches)}: {reason}" for reason, whiches in found.items())


def cell(row: pd.Series | None) -> str:
    """P / V / A / force, µs per step; the setting where the cell is a rung."""
    if row is None:
        return "none"
    if row["status"] != "ok":
        return f"{row['status']}: {str(row['message'])[:80]}"
    errors = " / ".join(_e(float(row[c])) for c in LEVELS)
    steps = float(row["steps"]) if float(row["steps"] or 0) > 0 else math.nan
    micro = 1e6 * float(row["run_time"]) / steps
    return f"{errors}, {micro:.0f} µs" if not math.isnan(micro) else errors


def picked(rows: pd.DataFrame) -> dict[str, pd.Series | None]:
    """The untuned, default and best rows of one scenario-engine group."""
    ok = rows[rows["status"] == "ok"].copy()
    ok["worst"] = ok[MOTION].astype(float).max(axis=1, skipna=True)
    untuned = rows[rows["is_untuned"].fillna(False).astype(bool)] if "is_untuned" in rows else rows[:0]
    default = rows[rows["is_default"].astype(bool)]
    best = ok.loc[ok["worst"].idxmin()] if ok["worst"].notna().any() else None
    return {
        "untuned": untuned.iloc[0] if len(untuned) else None,
        "default": default.iloc[0] if len(default) else None,
        "best": best,
    }


def engine_table(rows: pd.DataFrame) -> list[str]:
    """Per engine, a table of the scenarios' untuned, default and best cells."""
    lines: list[str] = []
    for engine in ENGINES:
        lines += [
            f"### {engine}",
            "",
            "| scenario | untuned | default | best (setting) | forces not given |",
            "|---|---|---|---|---|",
        ]
        for name in SCENARIOS:
            group = rows[(rows["scenario"] == name) & (rows["engine"] == engine)]
            if group.empty:
                lines.append(f"| {name} | not run | | | |")
                continue
            if not (group["status"] == "ok").any():
                first = group.iloc[0]
                lines.append(f"| {name} | {first['status']}: {str(first['message'])[:100]} | | | |")
                continue
            chosen = picked(group)
            best = chosen["best"]
            best_text = f"{cell(best)} ({best['setting']})" if best is not None else "none"
            untuned = cell(chosen["untuned"]) if chosen["untuned"] is not None else "none declared"
            lines.append(
                f"| {name} | {untuned} | {cell(chosen['default'])} | {best_text} | {forceless(chosen)} |"
            )
        lines.append("")
    return lines


def verdict_table(rows: pd.DataFrame) -> list[str]:
    """The four-bar's default at each output count: P / V / A / force per engine."""
    lines = [
        "| engine | " + " | ".join(f"{n} outputs" for n in OUTPUTS) + " |",
        "|---|" + "---|" * len(OUTPUTS),
    ]
    for engine in ENGINES:
        found = []
        for n in OUTPUTS:
            mine = rows[(rows["scenario"] == f"four_bar[steps={n}]") & (rows["engine"] == engine)]
            mine = mine[mine["is_default"].astype(bool)]
            found.append(" / ".join(_e(float(mine.iloc[0][c])) for c in LEVELS) if len(mine) else "none")
        lines.append(f"| {engine} | " + " | ".join(found) + " |")
    return lines


def page_text(table: pd.DataFrame, verdicts: pd.DataFrame) -> str:
    """The generated part of the page."""
    lines = [
        BEGIN,
        "",
        "Errors at position / velocity / acceleration / force, relative as the report measures them; "
        "CPU µs per engine step (per output time where the engine has no step) of one timed run on "
        "the shared machine. Generated by `python -m benchmarks.engine_table`.",
        "",
        *engine_table(table),
        "### four_bar's default against the number of outputs over its turn",
        "",
        *verdict_table(verdicts),
        "",
        END,
    ]
    return "\n".join(lines)


def write_page(page: Path, text: str) -> None:
    """Replace the page's text between BEGIN and END with `text` (append both where absent)."""
    old = page.read_text() if page.exists() else ""
    if BEGIN in old and END in old:
        head, rest = old.split(BEGIN, 1)
        new = head + text + rest.split(END, 1)[1]
    else:
        new = old + ("\n" if old else "") + text + "\n"
    page.write_text(new)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, help="results store directory (default: a temporary one)")
    parser.add_argument("--page", type=Path, default=PAGE, help="the page to write between its markers")
    args = parser.parse_args(argv)
    with tempfile.TemporaryDirectory(prefix="engine-table-") as scratch:
        out = args.out or Path(scratch)
        table = run_cells(out / "ladders", list(SCENARIOS), ladder=True)
        verdicts = run_cells(out / "outputs", [f"four_bar[steps={n}]" for n in OUTPUTS], ladder=False)
        text = page_text(table, verdicts)
    write_page(args.page, text)
    print(text)


if __name__ == "__main__":
    main()
