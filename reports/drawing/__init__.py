"""The mechanism drawn: a scenario at a time t (or over a cycle) as a labelled, self-contained SVG.

It solves the scenario with the native solver, so it sits apart from `reports/render`, which reads
stored results only."""

from reports.drawing.drawing import draw_svg

__all__ = ["draw_svg"]
