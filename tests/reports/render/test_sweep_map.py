"""The swept stability map: a four-bar sweep whose longer crank meets a dead point (the Grashof
limit crossed: coupler and rocker fold into line) shows the native solver's singular stop in that
cell, at the time the closed form gives, and ok cells elsewhere."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
from matplotlib.colors import to_rgba

from reports.render import html, markdown, markup, sweep_render
from reports.render.report_data import ReportData
from reports.render.swept_map import SINGULAR, swept_maps
from reports.run.runner import RunConfig, Runner
from reports.run.sweep import points
from reports.store.results_store import ResultsStore
from reports.stress.recording import record

GROUND, COUPLER, ROCKER, THETA0 = 0.1, 0.1, 0.125, 0.3  # the four_bar family's defaults
CRANKS, SPEEDS = ("0.05", "0.08"), ("10", "50")


def dead_point_time(crank: float, omega: float) -> float:
    """When the crank angle reaches the dead point: |A O4| = rocker - coupler (links folded), from
    the law of cosines; the crank turns from THETA0 towards 2 pi, where |A O4| is smallest."""
    folded = ROCKER - COUPLER
    cosine = (crank**2 + GROUND**2 - folded**2) / (2 * crank * GROUND)
    if abs(cosine) > 1:
        return math.inf  # a Grashof crank-rocker: the folded length is never reached
    return (2 * math.pi - math.acos(cosine) - THETA0) / omega


@pytest.fixture(scope="module")
def data(tmp_path_factory: pytest.TempPathFactory) -> ReportData:
    directory = tmp_path_factory.mktemp("sweep")
    names = points(["four_bar"], [f"crank_length={','.join(CRANKS)}", f"omega={','.join(SPEEDS)}"])
    config = RunConfig(ladder=False, repeats=1, warmup=0, timeout=120.0)
    Runner(ResultsStore(directory), ["reference"], config, progress=False).run(names)
    store = ResultsStore(directory)
    record(store, "")  # as `mbxval run` does once its runs are stored
    store.save(store.meta)
    return ReportData.load(directory)


def test_the_dead_point_is_in_the_longer_crank_s_cells(data: ReportData) -> None:
    (swept,) = swept_maps(data)
    assert swept.base == "four_bar" and swept.axes == ("crank_length", "omega")
    assert swept.values == ((0.05, 0.08), (10.0, 50.0))
    assert swept.native_singular() == {(1, 0), (1, 1)}
    for speed in SPEEDS:
        ok = swept.cell("reference", crank_length="0.05", omega=speed)
        assert math.isinf(dead_point_time(0.05, float(speed)))
        assert ok.verdict == "ok" and ok.error < 1e-12
        stopped = swept.cell("reference", crank_length="0.08", omega=speed)
        expected = dead_point_time(0.08, float(speed))
        step = 2 * math.pi / float(speed) / 200
        assert stopped.verdict == SINGULAR and abs(stopped.time - expected) < step


def test_the_heat_map_colours_that_cell(data: ReportData) -> None:
    (swept,) = swept_maps(data)
    image, seen = sweep_render._image(swept, "reference", {})
    assert image.shape == (2, 2, 4)  # omega up, crank length across
    singular = to_rgba(sweep_render.VERDICT_COLOURS[SINGULAR])
    for y in (0, 1):
        assert tuple(image[y, 1]) == singular
        assert tuple(image[y, 0]) == sweep_render.ERRORS(0.0)  # the smallest errors: full green
    assert seen == {SINGULAR}
    assert np.all(image[..., 3] == 1.0)


def test_the_report_sections_name_the_singular_points(data: ReportData) -> None:
    fragment = sweep_render.html_fragment(data)
    assert "Native solver singular at (0.08, 10), (0.08, 50)." in fragment
    assert fragment.count('<svg class="plot"') == 1
    # every cell says its swept values, verdict and error on hover (2 x 2 points, one engine)
    titles = re.findall(r"<title>(reference on four_bar at [^<]*)</title>", fragment)
    assert len(titles) == 4
    assert "reference on four_bar at crank_length=0.08, omega=50: singular detected" in " ".join(titles)
    summary = markdown.render(data)
    point = markup.markdown_text("four_bar[crank_length=0.08,omega=10]")  # brackets escaped as text
    assert f"| {point} | singular detected @0.5815 s |" in summary
    assert "## four_bar[" not in summary  # swept points are in the sweep's table, not sections


def test_the_page_opens_with_the_map_and_says_how_the_runs_were_timed(data: ReportData) -> None:
    page = html.render(data)
    assert page.index("Stability over the swept parameters") < page.index("Error against run time")
    assert 'id="s-four_bar' not in page  # no section per swept point
    assert "Run times measured on " in page and "one at a time" in page
