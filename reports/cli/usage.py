"""The command line's error convention (one line `mbxval: error: ...`, exit status 2) and the
arguments several commands share."""

from __future__ import annotations

import argparse
from collections.abc import Sequence
from typing import NoReturn

from reports.run import engine_packages
from reports.store import provenance


class UsageError(Exception):
    """Bad input from the user: reported as one line with exit status 2."""


class Parser(argparse.ArgumentParser):
    """argparse with its errors on one line, like every other error of mbxval."""

    def error(self, message: str) -> NoReturn:
        self.exit(2, f"mbxval: error: {message} (see `{self.prog} --help`)\n")


def pairs(items: Sequence[str], what: str) -> dict[str, str]:
    pairs = {}
    for item in items:
        key, sep, value = item.partition("=")
        if not sep or not key:
            raise UsageError(f"{what} expects NAME=VALUE, got '{item}'")
        pairs[key] = value
    return pairs


def scenario_argument(parser: argparse.ArgumentParser) -> None:
    """The positional SCENARIO (a name or a scenario file) and its `--set` overrides."""
    parser.add_argument(
        "scenario", help="scenario name, family/variant (see `mbxval list`), or a scenario file (.toml)"
    )
    parser.add_argument(
        "--set",
        action="append",
        default=[],
        metavar="NAME=VALUE",
        help="family parameter, or a scenario file's value by dotted key path",
    )


class Versions(argparse.Action):
    """`--version`: our version, Python's and every package's we run on, the engines' read from the
    registry only when asked (reading them imports every engine, which no other command needs)."""

    def __init__(self, option_strings: Sequence[str], dest: str = argparse.SUPPRESS, help: str = "") -> None:
        super().__init__(option_strings, dest, nargs=0, default=argparse.SUPPRESS, help=help)

    def __call__(
        self,
        parser: argparse.ArgumentParser,
        namespace: argparse.Namespace,
        values: object,
        option_string: str | None = None,
    ) -> NoReturn:
        print(provenance.version_text(engine_packages()))
        parser.exit()
