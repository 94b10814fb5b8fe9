"""The command line: list, solve and export in main; run, report, check and bench in suite_commands;
compare in compare_command. The Python API (mbxval) drives the same functions."""

from typing import TYPE_CHECKING

from reports.face import load

if TYPE_CHECKING:  # the face: what the package offers, each loaded on first use (reports.face)
    from reports.cli.compare_command import check_label as check_label
    from reports.cli.main import main as command_line  # noqa: F401 (its module bears the name main)
    from reports.cli.main import parser as parser
    from reports.cli.main import solve_trajectory as solve_trajectory
    from reports.cli.suite_commands import run_and_render as run_and_render
    from reports.cli.suite_commands import select as select
    from reports.cli.usage import UsageError as UsageError


def __getattr__(name: str) -> object:
    return load(__name__, name)
