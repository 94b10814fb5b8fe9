"""The gate: a stored run judged against a baseline of cells; its verdict written as JUnit XML or
JSON (files), and the baselines that ship with the package (baselines)."""

from typing import TYPE_CHECKING

from reports.face import load

if TYPE_CHECKING:
    from reports.gate import baselines, files
    from reports.gate.gate import (
        DEFAULT_FACTOR,
        GateError,
        describe,
        judge,
        read_baseline,
        updatable_cells,
        update_baseline,
    )

__all__ = [
    "DEFAULT_FACTOR",
    "GateError",
    "baselines",
    "describe",
    "files",
    "judge",
    "read_baseline",
    "updatable_cells",
    "update_baseline",
]


def __getattr__(name: str) -> object:
    return load(__name__, name)
