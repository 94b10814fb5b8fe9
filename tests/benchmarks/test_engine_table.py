"""benchmarks.engine_table: the page's text between its markers is replaced and the rest kept; a
cell without forces quotes the reason its row names."""

from __future__ import annotations

import math
from pathlib import Path

import pandas as pd

from benchmarks.engine_table import BEGIN, END, forceless, write_page


def test_only_the_text_between_the_markers_is_replaced(tmp_path: Path) -> None:
    page = tmp_path / "page.md"
    page.write_text(f"intro\n\n{BEGIN}\nold\n{END}\n\nafter\n")
    write_page(page, f"{BEGIN}\nnew\n{END}")
    assert page.read_text() == f"intro\n\n{BEGIN}\nnew\n{END}\n\nafter\n"


def test_a_row_without_forces_quotes_its_reason_or_says_none_is_named() -> None:
    def row(warnings: str, force: float = math.nan) -> pd.Series:
        return pd.Series({"status": "ok", "error_force": force, "warnings": warnings, "message": ""})

    named = row("UserWarning: forces not given: a gear as a mimic joint | other")
    chosen = {"untuned": None, "default": named, "best": row("", 1e-9)}
    assert forceless(chosen) == "default: forces not given: a gear as a mimic joint"
    assert forceless({"untuned": None, "default": row(""), "best": row("")}) == "default, best: none named"
