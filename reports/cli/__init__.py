"""The command line: list, solve and export in main; run, report, check and bench in suite_commands;
compare in compare_command. The Python API (mbxval) drives the same functions."""

from typing import TYPE_CHECKING

from reports.face import load

if TYPE_CHECKING:
    from reports.cli.compare_command import check_label
    from reports.cli.main import main as command_line
    from reports.cli.main import parser, solve_trajectory
    from reports.cli.suite_commands import run_and_render, select
    from reports.cli.usage import UsageError

__all__ = [
    "UsageError",
    "check_label",
    "command_line",
    "parser",
    "run_and_render",
    "select",
    "solve_trajectory",
]


def __getattr__(name: str) -> object:
    return load(__name__, name)
