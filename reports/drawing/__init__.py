"""The mechanism drawn: a scenario at a time t (or over a cycle) as a labelled, self-contained SVG.

It solves the scenario with the native solver, so it sits apart from `reports/render`, which reads
stored results only. `files`: a run's drawings, left beside its results for its
report."""

from typing import TYPE_CHECKING

from reports.face import load

if TYPE_CHECKING:  # the face: what the package offers, each loaded on first use (reports.face)
    from reports.drawing import files as files
    from reports.drawing.drawing import MAX_FRAMES as MAX_FRAMES
    from reports.drawing.drawing import DrawingError as DrawingError
    from reports.drawing.drawing import draw_svg as draw_svg


def __getattr__(name: str) -> object:
    return load(__name__, name)
