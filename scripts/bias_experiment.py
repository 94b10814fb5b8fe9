"""The injected-bias experiment: does the test suite fail when one engine's accelerations are off by
a small relative bias?

For each engine, runs the README's test command (the whole suite, slow tests included) with the
plugin `tests.support.bias_injection`, which multiplies every acceleration that engine returns by
1 + bias (`reference` biases the native solver, its truths included), and prints whether the suite
failed, how many tests failed and the first of them. A suite that passes under a bias is a hole in
the tests; the script exits 1 then.

    .venv/bin/python scripts/bias_experiment.py                 # every engine, 1 %, stop at the first failure
    .venv/bin/python scripts/bias_experiment.py --engine exudyn --bias 0.003 --all
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import time
from pathlib import Path

import adapters

ROOT = Path(__file__).resolve().parent.parent
ENGINES = tuple(adapters.names())


def run_suite(engine: str, bias: float, every: bool, selection: list[str]) -> tuple[int, list[str], float]:
    """The suite's exit status, the failed test ids and the wall time, under the injected bias."""
    env = dict(os.environ, MBXVAL_BIAS_ENGINE=engine, MBXVAL_BIAS=repr(bias))
    command = [sys.executable, "-m", "pytest", "-q", "-rf", "-p", "tests.support.bias_injection"]
    command += [] if every else ["-x"]
    command += selection
    start = time.perf_counter()
    done = subprocess.run(command, cwd=ROOT, env=env, capture_output=True, text=True, check=False)
    failed = re.findall(r"^FAILED (\S+)", done.stdout, flags=re.MULTILINE)
    return done.returncode, failed, time.perf_counter() - start


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--engine", action="append", choices=ENGINES, help="default: every engine")
    parser.add_argument("--bias", type=float, default=0.01, help="relative bias (default 0.01)")
    parser.add_argument("--all", action="store_true", help="run on after the first failure, to count")
    parser.add_argument("selection", nargs="*", help="test paths (default: the whole suite)")
    args = parser.parse_args(argv)
    if not 0.0 < abs(args.bias) <= 1.0:
        parser.error(f"--bias {args.bias}: must be within (0, 1] in magnitude")
    holes = 0
    for engine in args.engine or ENGINES:
        status, failed, seconds = run_suite(engine, args.bias, args.all, args.selection)
        caught = status == 1 and failed
        holes += not caught
        verdict = "caught" if caught else f"NOT caught (pytest exit {status})"
        first = f"; first: {failed[0]}" if failed else ""
        print(f"{engine:10s} bias {args.bias:g}: {verdict}, {len(failed)} failed in {seconds:.0f} s{first}")
        sys.stdout.flush()
    return 1 if holes else 0


if __name__ == "__main__":
    sys.exit(main())
