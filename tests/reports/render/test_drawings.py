"""A run draws its mechanisms beside its results and the report shows them as stored, as images:
a drawing planted in a results directory can carry no script into the page."""

from __future__ import annotations

import base64
import json
from pathlib import Path

from reports.cli.main import main
from reports.render.drawings import DRAWINGS, INDEX
from reports.render.report import render_reports

IMAGE = '<img class="drawing" src="data:image/svg+xml;base64,'


def test_a_run_s_report_shows_each_scenario_s_drawing_as_an_image(tmp_path: Path) -> None:
    out = tmp_path / "out"
    argv = ["run", "--suite", "quick", "--scenario", "slider_crank", "--engine", "reference"]
    assert main([*argv, "--out", str(out), "--quiet"]) == 0
    index = json.loads((out / DRAWINGS / INDEX).read_text())
    assert list(index) == ["slider_crank"]
    page = (out / "index.html").read_text()
    assert page.count(IMAGE) == 1
    encoded = page.split(IMAGE, 1)[1].split('"', 1)[0]
    assert base64.b64decode(encoded).decode() == (out / DRAWINGS / index["slider_crank"]).read_text()
    alt = page.split(IMAGE, 1)[1].split('alt="', 1)[1].split('"', 1)[0]
    assert alt == "slider_crank: one cycle (0.125664 s) in 12 frames"  # 2 pi / the default 50 rad/s

    planted = '<svg xmlns="http://www.w3.org/2000/svg"><script>alert("x")</script></svg>'
    (out / DRAWINGS / index["slider_crank"]).write_text(planted)
    page = render_reports(out).read_text()
    assert 'alert("x")' not in page and page.count(IMAGE) == 1
