"""The mechanism drawn: a scenario at a time t (or over a cycle) as a labelled, self-contained SVG.

It solves the scenario with the native solver, so it sits apart from `reports/render`, which reads
stored results only. `files`: a run's drawings, left beside its results for its
report."""

from typing import TYPE_CHECKING

from reports.face import load

if TYPE_CHECKING:
    from reports.drawing import files
    from reports.drawing.drawing import MAX_FRAMES, DrawingError, draw_svg

__all__ = ["MAX_FRAMES", "DrawingError", "draw_svg", "files"]


def __getattr__(name: str) -> object:
    return load(__name__, name)
