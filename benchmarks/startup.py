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
interpreter's `mbxval` (`python -m reports.entry` would not: it is the module the script runs)."""

from __future__ import annotations

import argparse
import os
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


def load() -> str:
    with open("/proc/loadavg") as loadavg:
        return " ".join(loadavg.read().split()[:3])


def main(argv: list[str] | None = None) -> dict[tuple[str, str], Cost]:
    parser = argparse.ArgumentParser(prog="startup", description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3, help="turns of every command (default 3)")
    parser.add_argument("--case", action="append", choices=list(CASES), help="only these (repeatable)")
    args = parser.parse_args(argv)
    chosen = [c for c in CASES if c in (args.case or CASES) or c in (NUMPY, START_UP)]
    print(f"load before: {load()}; {os.cpu_count()} cores; best of {args.repeats} by CPU")
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
    print(f"load after: {load()}")
    return best


if __name__ == "__main__":
    main()
