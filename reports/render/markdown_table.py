"""GitHub-flavoured Markdown tables from data frames: a leaf module shared by the Markdown renderers."""

from __future__ import annotations

import pandas as pd

from reports.render.markup import markdown_text


def markdown_table(frame: pd.DataFrame, index_name: str | None = None) -> str:
    """A GitHub-flavoured Markdown table (every heading and cell through markup.markdown_text)."""
    columns = ([index_name] if index_name else []) + [str(c) for c in frame.columns]
    lines = ["| " + " | ".join(markdown_text(c) for c in columns) + " |", "|" + "---|" * len(columns)]
    for index, row in frame.iterrows():
        cells = ([str(index)] if index_name else []) + [str(v) for v in row]
        lines.append("| " + " | ".join(markdown_text(c) for c in cells) + " |")
    return "\n".join(lines)
