"""The gate: a stored run judged against a baseline of cells; its verdict written as JUnit XML or
JSON (files), and the baselines that ship with the package (baselines)."""

from typing import TYPE_CHECKING

from reports.face import load

if TYPE_CHECKING:  # the face: what the package offers, each loaded on first use (reports.face)
    from reports.gate import baselines as baselines
    from reports.gate import files as files
    from reports.gate.gate import DEFAULT_FACTOR as DEFAULT_FACTOR
    from reports.gate.gate import GateError as GateError
    from reports.gate.gate import describe as describe
    from reports.gate.gate import judge as judge
    from reports.gate.gate import read_baseline as read_baseline
    from reports.gate.gate import updatable_cells as updatable_cells
    from reports.gate.gate import update_baseline as update_baseline


def __getattr__(name: str) -> object:
    return load(__name__, name)
