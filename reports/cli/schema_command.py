"""`mbxval schema`: the JSON Schema of the scenario file (scenarios.files.json_schema), for editors."""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Callable

from reports.store import write_text
from scenarios.files.json_schema import scenario_schema


def cmd_schema(args: argparse.Namespace) -> int:
    text = json.dumps(scenario_schema(), indent=1) + "\n"
    if args.out is None:
        sys.stdout.write(text)
        return 0
    write_text(args.out, text)
    print(f"wrote {args.out}")
    return 0


def add_parser(sub: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    """Add `schema` to the command line."""
    schema = sub.add_parser("schema", help="the JSON Schema of the scenario file, for editors")
    schema.add_argument("--out", help="file to write (default: stdout)")


COMMANDS: dict[str, Callable[[argparse.Namespace], int]] = {"schema": cmd_schema}
