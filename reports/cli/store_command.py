"""`mbxval store repair DIR`: bring a results store back to a state mbxval understands (see
reports.store.repair), under the store's writer lock, saying what was done."""

from __future__ import annotations

import argparse
from collections.abc import Callable
from pathlib import Path
from typing import Any

from reports.store import WriterLock


def cmd_store(args: argparse.Namespace) -> int:
    from reports.store import Repair, holds_a_store  # pandas: imported when it runs

    directory = Path(args.directory)
    if not holds_a_store(directory):  # before the lock, which would leave its file there
        raise FileNotFoundError(f"no results store at {directory}")
    with WriterLock(directory, wait=args.wait):
        lines = Repair(directory).run()
    print("\n".join(f"{directory}: {line}" for line in lines))
    return 0


def add_parser(sub: Any) -> None:
    store = sub.add_parser("store", help="look after a results store (repair)")
    actions = store.add_subparsers(dest="action", required=True, parser_class=type(store))
    repair = actions.add_parser(
        "repair",
        help="keep every generation that verifies, point `current` at the newest, restore the links",
    )
    repair.add_argument("directory", metavar="DIR", help="the results directory")
    repair.add_argument("--wait", action="store_true", help="wait for another run writing DIR to end")


COMMANDS: dict[str, Callable[[argparse.Namespace], int]] = {"store": cmd_store}
