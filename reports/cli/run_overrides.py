"""What `solve` takes, for `run` and `check`: `--set NAME=VALUE`, `--t-end` and `--steps`, applied to
every scenario of the run. Each becomes part of the scenario's name in the bracket form of a swept
point (`slider_crank[offset=0.05,t_end=0.5]`, scenarios.loading), so that the run stores its rows
under a name of their own, from which the scenario is rebuilt anywhere (a Dask worker, a report)."""

from __future__ import annotations

import argparse
from collections.abc import Mapping, Sequence

from reports.cli.usage import UsageError, pairs
from scenarios import load
from scenarios.loading import split_point
from scenarios.scenario import POINT_RESERVED, point_name


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """The options `solve` shares with `run`."""
    parser.add_argument(
        "--set",
        action="append",
        default=[],
        metavar="NAME=VALUE",
        help="set a parameter of every scenario of the run (a family's, or a file's dotted key)",
    )
    parser.add_argument("--t-end", type=float, help="end time of every scenario (default: each one's)")
    parser.add_argument("--steps", type=int, help="equal steps of every scenario's grid (default: its own)")


def overrides(args: argparse.Namespace) -> dict[str, str]:
    """The values the options give, by the scenario key each sets."""
    values = pairs(getattr(args, "set", []), "--set")
    if getattr(args, "t_end", None) is not None:
        values["t_end"] = repr(args.t_end)
    if getattr(args, "steps", None) is not None:
        values["steps"] = str(args.steps)
    return values


def apply(names: Sequence[str], values: Mapping[str, str]) -> list[str]:
    """Every name with `values` added to its point (they win over a swept value of the same key);
    each scenario is built, so an unknown parameter or a value out of range is one error here."""
    if not values:
        return list(names)
    for key, value in values.items():
        if any(c in POINT_RESERVED for c in key + value):
            raise UsageError(f"--set {key}={value}: a name or value cannot hold any of {POINT_RESERVED}")
    out = []
    for name in names:
        base, point = split_point(name)
        out.append(point_name(base, {**point, **values}))
        load(out[-1])
    return out
