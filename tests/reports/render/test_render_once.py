"""What the report's render no longer repeats or waits for, and that its output stays the same:
a tight-laid-out figure is drawn once (savefig drew it once more, without output, for the
placeholder engine `tight_layout()` leaves), and the scenarios' sections are drawn by forked workers
while this process draws the rest of the page (the dynamics figures among it), not after it."""

from __future__ import annotations

import os
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.figure import Figure
from matplotlib.layout_engine import LayoutEngine

from reports.cli.main import main
from reports.render import dynamics_render, html, svg_figure
from reports.render.report_data import ReportData

SCENARIOS = [
    "compound_pendulum",
    "compound_pendulum/small_oscillation",
    "stiff_spring/k1e2_dt1e-2",
    "stiff_spring/k1e4_dt1e-2",
]


class _Inert(LayoutEngine):
    """A layout engine that lays out nothing, as the placeholder does, but is not the placeholder:
    savefig draws a figure holding it once without output before the draw that writes, as it did
    with every tight-laid-out figure before."""

    _adjust_compatible = True
    _colorbar_gridspec = True

    def execute(self, fig: Figure) -> None:
        return None


def _tight_figure() -> Figure:
    """A figure like the dynamics section's: log axes in a grid, a legend, tight_layout."""
    figure, grid = plt.subplots(2, 2, figsize=(8.6, 5.2), squeeze=False)
    times = np.linspace(0.0, 1.0, 201)
    for k, axes in enumerate(grid.ravel()):
        axes.semilogy(times, 1e-9 + np.abs(np.sin((k + 1) * 7 * times)) * 1e-6, label=f"run {k}")
        axes.set_title(f"panel {k}", fontsize=9)
        axes.set_xlabel("t [s]", fontsize=8)
    figure.legend(loc="upper right", fontsize=8)
    figure.tight_layout(rect=(0, 0, 0.9, 1))
    return figure


def _draws(figure: Figure) -> list[str]:
    seen: list[str] = []
    figure.canvas.mpl_connect("draw_event", lambda event: seen.append(event.name))
    return seen


def test_a_tight_laid_out_figure_is_drawn_once_and_writes_the_same_svg() -> None:
    kept = _tight_figure()
    kept.set_layout_engine(_Inert())  # what savefig met before: a layout engine, so a draw first
    kept_draws = _draws(kept)
    before = svg_figure.svg(kept, "drift")
    now = _tight_figure()
    now_draws = _draws(now)
    after = svg_figure.svg(now, "drift")
    assert len(kept_draws) == 2 and len(now_draws) == 1
    assert after == before


def test_a_figure_with_a_layout_engine_of_its_own_keeps_it() -> None:
    figure, axes = plt.subplots(layout="constrained")
    axes.plot([0.0, 1.0], [0.0, 1.0])
    engine = figure.get_layout_engine()
    svg_figure.laid_out(figure)
    assert figure.get_layout_engine() is engine
    plt.close(figure)


def test_a_matplotlibrc_asking_for_autolayout_does_not_bring_a_layout_back(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setitem(matplotlib.rcParams, "figure.autolayout", True)
    figure = _tight_figure()
    svg_figure.laid_out(figure)
    assert figure.get_layout_engine() is None
    plt.close(figure)


@pytest.fixture(scope="module")
def data(tmp_path_factory: pytest.TempPathFactory) -> ReportData:
    """A real narrow dynamics run of the native engine: two map cells (the dynamics map and its
    figures) and two scenarios with sections of their own, for two forked workers."""
    out = tmp_path_factory.mktemp("render-once")
    args = ["run", "--suite", "dynamics", "--engine", "reference", "--out", str(out), "--quiet"]
    for name in SCENARIOS:
        args += ["--scenario", name]
    assert main(args) == 0
    return ReportData.load(Path(out))


def test_the_page_is_the_same_drawn_in_one_process_or_with_forked_sections(
    data: ReportData, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(os, "cpu_count", lambda: 2)
    forked = html.render(data)
    monkeypatch.setattr(html, "WORKERS", 1)
    assert html.render(data) == forked


def test_the_sections_are_being_drawn_while_the_dynamics_figures_are(
    data: ReportData, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The workers are forked (and given the sections) before this process draws the dynamics
    section: the data they draw from is handed over by then."""
    monkeypatch.setattr(os, "cpu_count", lambda: 2)
    seen: list[bool] = []
    fragment = dynamics_render.html_fragment

    def watched(*args: object, **kwargs: object) -> str:
        seen.append("data" in html._FORKED)
        return fragment(*args, **kwargs)  # type: ignore[arg-type]

    monkeypatch.setattr(dynamics_render, "html_fragment", watched)
    page = html.render(data)
    assert seen == [True] and "Energy drift over time" in page
    assert not html._FORKED  # handed back when the page is done
