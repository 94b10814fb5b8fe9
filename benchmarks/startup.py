"""What the command line costs from a fresh process: CPU (user + system, the process and the
children it reaped), wall time and peak memory of each command, with and without
OPENBLAS_NUM_THREADS=1, each also as a ratio to one start-up (`mbxval solve four_bar --steps 1`)
and to `python -c "import numpy"` measured in the same run, the commands taking turns so that a
burst of load falls on all alike.

    python -m benchmarks.startup [--repeats 3] [--case NAME ...]

Cases: numpy's import; `mbxval --help`; the start-up; a 16-point native sweep (`mbxval run
--scenario four_bar --engine reference --sweep omega=lin:10:40:16`, its report included);
Andrews' squeezer to 0.03 s; IFToMM A02 with two loops over 10 s by ALI3-P. The figures are the
best of --repeats by CPU; the load average is printed before and after. The commands run this
interpreter's `mbxval` (`python -m reports.entry` would not: it is the module the script runs).
With --write PAGE, the figures also replace the Markdown table between the page's BEGIN and END
markers (docs/performance.md's), with the load and the core count, so that the page's figures are
the benchmark's, never copied by hand."""

from __future__ import annotations

import argparse
import os
import platform
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

NUMPY = "import numpy"
START_UP = "start-up"
CASES: dict[str, list[str]] = {
    NUMPY: [],
    "--help": ["--help"],
    START_UP: ["solve", "four_bar", "--steps", "1"],
    "16-point native sweep": [
        "run", "--scenario", "four_bar", "--engine", "reference", "--sweep", "omega=lin:10:40:16", "--quiet",
    ],
    "Andrews to 0.03 s": ["solve", "andrews_squeezer", "--t-end", "0.03"],
    "A02 N=2, 10 s, ALI3-P": ["solve", "n_four_bar", "--set", "t_end=10", "--mode", "ali3p"],
}  # fmt: skip
"""Each case's `mbxval` arguments (numpy's import: none, it is `python -c "import numpy"`)."""
ENTRY = "import sys; from reports.entry import main; sys.exit(main(sys.argv[1:]))"
VARIANTS = {"default": {}, "OPENBLAS_NUM_THREADS=1": {"OPENBLAS_NUM_THREADS": "1"}}


@dataclass(frozen=True)
class Cost:
    cpu: float
    wall: float
    rss_mb: float


def command(case: str, out: Path) -> list[str]:
    """The process to start for `case`, its output directory (a sweep's) under `out`."""
    if case == NUMPY:
        return [sys.executable, "-c", NUMPY]
    arguments = CASES[case]
    if arguments[0] == "run":
        arguments = [*arguments, "--out", str(out)]
    return [sys.executable, "-c", ENTRY, *arguments]


def cost(argv: list[str], extra_env: dict[str, str]) -> Cost:
    """CPU, wall and peak RSS of one process (wait4: its own and its reaped children's CPU)."""
    env = {**os.environ, **extra_env}
    start = os.times().elapsed
    child = subprocess.Popen(argv, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(child.pid, 0)
    wall = os.times().elapsed - start
    child.returncode = os.waitstatus_to_exitcode(status)
    if child.returncode != 0:
        error = child.stderr.read().decode() if child.stderr else ""
        raise SystemExit(f"{' '.join(argv[3:])} failed ({child.returncode}): {error.strip()[-300:]}")
    return Cost(usage.ru_utime + usage.ru_stime, wall, usage.ru_maxrss / 1024)


BEGIN = "<!-- benchmarks.startup: begin -->"
END = "<!-- benchmarks.startup: end -->"
DESCRIBED = {
    NUMPY: '`python -c "import numpy"`',
    "--help": "`mbxval --help`",
    START_UP: "start-up: `mbxval solve four_bar --steps 1`",
    "16-point native sweep": "16-point native sweep (`mbxval run --scenario four_bar --engine reference "
    "--sweep omega=lin:10:40:16`, report included)",
    "Andrews to 0.03 s": "Andrews' squeezer to 0.03 s",
    "A02 N=2, 10 s, ALI3-P": "A02 N = 2 over 10 s, `--mode ali3p`",
}


def markdown(best: dict[tuple[str, str], Cost], repeats: int, loads: tuple[str, str]) -> str:
    """The figures as the performance page's table, with what they were measured under."""
    lines = [
        f"{os.cpu_count()} cores ({platform.machine()}), load average {loads[0]} before and {loads[1]} "
        f"after; best of {repeats} by CPU.",
        "",
        "| case | CPU s | wall s | peak RSS MB | / start-up | / numpy "
        "| CPU default / OPENBLAS_NUM_THREADS=1 |",
        "|---|---|---|---|---|---|---|",
    ]
    unit, numpy = best[(START_UP, "default")].cpu, best[(NUMPY, "default")].cpu
    for case in dict.fromkeys(case for case, _ in best):
        spent, single = best[(case, "default")], best[(case, "OPENBLAS_NUM_THREADS=1")]
        lines.append(
            f"| {DESCRIBED[case]} | {spent.cpu:.2f} | {spent.wall:.3g} | {spent.rss_mb:.0f} | "
            f"{spent.cpu / unit:.2f} | {spent.cpu / numpy:.1f} | {spent.cpu / single.cpu:.2f} |"
        )
    return "\n".join(lines) + "\n"


def write_between_markers(page: Path, text: str) -> None:
    """Replace what lies between the BEGIN and END lines of `page` with `text`; SystemExit where
    the page lacks them (nothing is written then)."""
    whole = page.read_text()
    start, end = whole.find(BEGIN), whole.find(END)
    if start < 0 or end < start:
        raise SystemExit(f"{page}: no '{BEGIN}' ... '{END}' markers to write between")
    page.write_text(whole[: start + len(BEGIN)] + "\n" + text + whole[end:])


def load() -> str:
    with open("/proc/loadavg") as loadavg:
        return " ".join(loadavg.read().split()[:3])


def main(argv: list[str] | None = None) -> dict[tuple[str, str], Cost]:
    parser = argparse.ArgumentParser(prog="startup", description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3, help="turns of every command (default 3)")
    parser.add_argument("--case", action="append", choices=list(CASES), help="only these (repeatable)")
    parser.add_argument("--write", type=Path, metavar="PAGE", help="write the table between PAGE's markers")
    args = parser.parse_args(argv)
    chosen = [c for c in CASES if c in (args.case or CASES) or c in (NUMPY, START_UP)]
    before = load()
    print(f"load before: {before}; {os.cpu_count()} cores; best of {args.repeats} by CPU")
    found: dict[tuple[str, str], list[Cost]] = {}
    with tempfile.TemporaryDirectory(prefix="mbxval-startup-") as temporary:
        for turn in range(max(1, args.repeats)):
            for case in chosen:
                for variant, env in VARIANTS.items():
                    out = Path(temporary) / f"{turn}-{variant}-{len(found)}"
                    found.setdefault((case, variant), []).append(cost(command(case, out), env))
    best = {key: min(costs, key=lambda c: c.cpu) for key, costs in found.items()}
    print(f"{'case':<24}{'variant':<24}{'CPU s':>7}{'wall s':>8}{'RSS MB':>8}{'/start-up':>10}{'/numpy':>8}")
    for (case, variant), spent in best.items():
        unit, numpy = best[(START_UP, variant)].cpu, best[(NUMPY, variant)].cpu
        print(
            f"{case:<24}{variant:<24}{spent.cpu:7.2f}{spent.wall:8.2f}{spent.rss_mb:8.0f}"
            f"{spent.cpu / unit:10.2f}{spent.cpu / numpy:8.1f}"
        )
    for case in chosen:
        alone, single = best[(case, "default")].cpu, best[(case, "OPENBLAS_NUM_THREADS=1")].cpu
        print(f"{case:<24}default / OPENBLAS_NUM_THREADS=1 in CPU: {alone / single:.2f}")
    after = load()
    print(f"load after: {after}")
    if args.write is not None:
        write_between_markers(args.write, markdown(best, max(1, args.repeats), (before, after)))
    return best


if __name__ == "__main__":
    main()
