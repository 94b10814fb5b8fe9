"""Reports rendered from stored results alone: HTML, Markdown and figures."""

from typing import TYPE_CHECKING

from reports.face import load

if TYPE_CHECKING:
    from reports.render.drawings import DRAWINGS, INDEX, read_index
    from reports.render.first_screen import BEST, WORST
    from reports.render.report import render_reports

__all__ = ["BEST", "DRAWINGS", "INDEX", "WORST", "read_index", "render_reports"]


def __getattr__(name: str) -> object:
    return load(__name__, name)
