"""The command line: list, solve and export in main; run, report, check and bench in suite_commands."""

from reports.cli.main import main

__all__ = ["main"]
