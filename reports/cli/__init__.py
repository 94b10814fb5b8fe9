"""The command line: list, solve and export in main; run, report, check and bench in suite_commands.

`main` here is the `mbxval` entry point. It imports the command line when called, so that a Ctrl-C
while numpy, the engines and the solver load ends like a Ctrl-C anywhere else: one line, exit 130.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence


def entry(argv: Sequence[str] | None = None) -> int:
    """Run the command line (reports.cli.main.main)."""
    try:
        from reports.cli.main import main as command_line
    except KeyboardInterrupt:
        print("mbxval: interrupted while starting", file=sys.stderr)
        return 130
    finally:
        globals()["main"] = entry  # the import rebinds the package's `main` to the submodule
    return command_line(argv)


main = entry

__all__ = ["main"]
