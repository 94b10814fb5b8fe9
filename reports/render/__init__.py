"""Reports rendered from stored results alone: HTML, Markdown and figures."""

from typing import TYPE_CHECKING

from reports.face import load

if TYPE_CHECKING:  # the face: what the package offers, each loaded on first use (reports.face)
    from reports.render.drawings import DRAWINGS as DRAWINGS
    from reports.render.drawings import INDEX as INDEX
    from reports.render.drawings import read_index as read_index
    from reports.render.first_screen import BEST as BEST
    from reports.render.first_screen import WORST as WORST
    from reports.render.report import render_reports as render_reports


def __getattr__(name: str) -> object:
    return load(__name__, name)
