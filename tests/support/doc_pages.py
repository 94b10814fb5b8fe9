"""The documentation pages as the docs' figure tests read them, and figures written as the pages
write them, so that a test can make the words a page must contain from a table of measured values."""

from __future__ import annotations

import re
from pathlib import Path

DOCS = Path(__file__).resolve().parents[2] / "docs"


def figure(value: float) -> str:
    """A figure as the docs write it: two digits, no padded exponent (7.9e-8)."""
    mantissa, exponent = f"{value:.1e}".split("e")
    return f"{mantissa}e{int(exponent)}"


def triple(values: tuple[float, ...]) -> str:
    return " / ".join(figure(v) for v in values)


def page_text(page: str) -> str:
    """docs/`page` with every run of white space made one space (a phrase may wrap anywhere)."""
    return re.sub(r"\s+", " ", (DOCS / page).read_text(encoding="utf-8"))
