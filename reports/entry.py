"""The `mbxval` console entry point. It imports the command line (reports.cli.main) only when
called, so that a Ctrl-C while numpy, the engines and the solver load ends like a Ctrl-C anywhere
else: one line, exit 130, instead of a traceback from inside an import. A command stopped by Ctrl-C
or SIGTERM ends at once once it has unwound (reports.run.stop.end). Its BLAS libraries start at
one thread (adapters.threads)."""

from __future__ import annotations

import os
import sys
from collections.abc import Sequence

BLAS_THREADS = "1"
"""adapters.threads.BLAS_THREADS, spelled here because importing adapters would load numpy first."""


def main(argv: Sequence[str] | None = None) -> int:
    os.environ["OPENBLAS_NUM_THREADS"] = BLAS_THREADS  # read when numpy loads OpenBLAS
    try:
        from reports.cli import command_line
    except KeyboardInterrupt:
        print("mbxval: interrupted while starting", file=sys.stderr)
        return 130
    from reports.run import stop  # loaded with the command line

    return stop.end(command_line(argv))
