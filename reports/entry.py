"""The `mbxval` console entry point. It imports the command line (reports.cli.main) only when
called, so that a Ctrl-C while numpy, the engines and the solver load ends like a Ctrl-C anywhere
else: one line, exit 130, instead of a traceback from inside an import. A command stopped by Ctrl-C
or SIGTERM ends at once once it has unwound (reports.run.stop.end)."""

from __future__ import annotations

import sys
from collections.abc import Sequence


def main(argv: Sequence[str] | None = None) -> int:
    try:
        from reports.cli import command_line
    except KeyboardInterrupt:
        print("mbxval: interrupted while starting", file=sys.stderr)
        return 130
    from reports.run import stop  # loaded with the command line

    return stop.end(command_line(argv))
