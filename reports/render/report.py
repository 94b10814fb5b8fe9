"""Render the reports of a results directory from its stored files alone."""

from __future__ import annotations

import os
from pathlib import Path

import reports.render.html as html_report
import reports.render.markdown as markdown_report
from reports.render.report_data import ReportData
from reports.store import atomic_output, results_directory

HTML, MARKDOWN = "index.html", "summary.md"


def render_reports(results: str | os.PathLike[str], out: str | os.PathLike[str] | None = None) -> Path:
    """Write index.html and summary.md for the results in `results` into `out` (default: the same
    directory); returns the HTML file's path."""
    data = ReportData.load(results)
    target = Path(out) if out is not None else results_directory(results)  # DIR, given its results.parquet
    target.mkdir(parents=True, exist_ok=True)
    with atomic_output(target / HTML) as stream:
        stream.write(html_report.render(data))
    with atomic_output(target / MARKDOWN) as stream:
        stream.write(markdown_report.render(data))
    return target / HTML
