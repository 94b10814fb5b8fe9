"""Every row a run calls drifted carries the ⚠ beside its errors in the page and in summary.md; and
summary.md writes every stored value as text (escaped) or as a code span no backtick closes."""

from __future__ import annotations

import dataclasses
import re
from pathlib import Path

import pytest

from reports.cli.main import main
from reports.render import markdown
from reports.render.report_data import ReportData
from reports.scoring import self_check
from reports.store.results_store import read_results

MARK = "⚠"


@pytest.fixture(scope="module")
def drifted(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A real run whose self-check limit on the residual is 0, so that every ok run with a nonzero
    residual is called drifted (the engines' soft constraints leave one)."""
    out = tmp_path_factory.mktemp("run")
    patch = pytest.MonkeyPatch()
    patch.setattr(self_check, "RESIDUAL_LIMIT", 0.0)
    try:
        argv = ["run", "--out", str(out), "--quiet", "--scenario", "slider_crank", "--engine", "mujoco"]
        assert main([*argv, "--repeats", "1", "--warmup", "0"]) == 0
    finally:
        patch.undo()
    return out


def cells(line: str) -> list[str]:
    return [c.strip() for c in re.split(r"(?<!\\)\|", line)[1:-1]]


def test_every_drifted_row_is_marked_in_summary_md(drifted: Path) -> None:
    frame, _ = read_results(drifted)
    marked = frame[(frame["status"] == "ok") & (frame["self_check"].fillna("") != "")]
    assert len(marked) >= 2
    lines = (drifted / "summary.md").read_text().splitlines()
    heading = cells(next(line for line in lines if line.startswith("| engine | setting |")))
    for _, row in marked.iterrows():
        found = [cells(line) for line in lines if line.startswith("| mujoco |") and row["setting"] in line]
        assert len(found) == 1, row["setting"]
        shown = dict(zip(heading, found[0], strict=True))
        assert all(shown[c].endswith(MARK) for c in ("error pos", "error vel", "error acc")), shown
    matrix = next(line for line in lines if line.startswith("| slider_crank |"))
    default = frame[frame["is_default"].astype(bool)].iloc[0]
    assert matrix.endswith(f"{MARK} |") == bool(default["self_check"])


def test_every_drifted_row_is_marked_in_the_page(drifted: Path) -> None:
    frame, _ = read_results(drifted)
    marked = int(((frame["status"] == "ok") & (frame["self_check"].fillna("") != "")).sum())
    page = (drifted / "index.html").read_text()
    # the legend, three errors in each drifted row's table line, the default's cells in the matrix
    assert page.count(MARK) >= 1 + 3 * marked


HOSTILE = {
    "suite": "quick` <img src=x onerror=alert(1)> ``x",
    "python": "3.11`<script>alert(2)</script>` *bold* [link](http://x)",
    "date": "2026|`a`",
    "machine": {"processor": "EPYC\n# heading", "cpus": "2`"},
    "git_revision": "abc`def",
}


def test_stored_fields_of_a_tampered_store_are_text_in_summary_md(drifted: Path) -> None:
    data = ReportData.load(drifted)
    text = markdown.render(dataclasses.replace(data, meta={**data.meta, **HOSTILE}))
    assert "<img" not in text.replace(HOSTILE["suite"], "") and "<script" not in text
    suite = re.search(r"^Suite (`+) ?(.*?) ?\1, ", text, re.MULTILINE)
    assert suite is not None and suite.group(2) == HOSTILE["suite"]  # one code span, closed by its own fence
    assert max(map(len, re.findall("`+", HOSTILE["suite"]))) < len(suite.group(1))
    python = next(line for line in text.splitlines() if line.startswith("Engines:"))
    assert "\\`&lt;script&gt;" in python and "\\*bold\\*" in python and "\\[link\\]" in python
    assert "\n# heading" not in text and "EPYC # heading" in text  # one line, no heading made
    assert "2026\\|\\`a\\`" in text
