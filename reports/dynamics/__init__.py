"""The dynamics suite: engines in forward dynamics against the native truth, its stability map.

Its parts: `cases` (the suite's scenarios, truth and settings) and `recording` (the map's verdicts
and drift series, stored when a run is made; it imports the native solver)."""

from typing import TYPE_CHECKING

from reports.face import load

if TYPE_CHECKING:  # the face: what the package offers, each loaded on first use (reports.face)
    from reports.dynamics import cases as cases
    from reports.dynamics import recording as recording


def __getattr__(name: str) -> object:
    return load(__name__, name)
