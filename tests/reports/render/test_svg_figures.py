"""The report's figures as SVG: they parse as XML, every plotted run carries a hover title with its
engine and values, an imported row (no run time) is drawn in its own strip without moving the
run-time axis, a sweep's narrow run-time axis carries several labels, and settings sort by value."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ElementTree

import matplotlib.pyplot as plt
import pandas as pd
import pytest
from matplotlib.figure import Figure

from reports.render import level_plots, overview, svg_figure
from reports.render.report_data import table

SVG = "{http://www.w3.org/2000/svg}"
TOLERANCES = (1e-6, 1e-8, 1e-10, 1e-4)  # as text these sort 0.0001, 1e-06, 1e-08, 1e-10


def row(
    engine: str, mode: str, setting: str, errors: tuple[float, float, float], time: float
) -> dict[str, object]:
    return {
        "scenario": "slider_crank", "engine": engine, "mode": mode, "setting": f"{mode} {setting}".strip(),
        "is_default": False, "status": "ok", "run_time": time, "error": max(errors),
        "error_position": errors[0], "error_velocity": errors[1], "error_acceleration": errors[2],
    }  # fmt: skip


def engine_rows() -> list[dict[str, object]]:
    """A tolerance sweep of a newton engine (narrow run times: 0.02 to 0.06 s, under half a decade)
    and a step sweep of another with no velocity level."""
    rows = [
        row("reference", "newton", f"tolerance={tol:g}", (tol, 2 * tol, 3 * tol), 0.02 + 0.01 * k)
        for k, tol in enumerate(TOLERANCES)
    ]
    rows += [
        row("mujoco", "RK4", f"dt={dt:g}", (10 * dt, math.nan, 100 * dt), 0.03 + 0.01 * k)
        for k, dt in enumerate((1e-3, 1e-4))
    ]
    rows[0]["is_default"] = True
    return rows


IMPORTED = row("my_tool", "imported", "", (1e-7, 1e-6, 1e-5), math.nan)


def drawn(figure: Figure | None, alt: str) -> str:
    assert figure is not None
    return svg_figure.svg(figure, alt)


def titles(svg: str) -> list[str]:
    root = ElementTree.fromstring(svg)  # the figure parses as XML
    assert root.tag == f"{SVG}svg"
    return [title.text or "" for title in root.iter(f"{SVG}title")]


def test_every_plotted_run_has_a_hover_title_with_its_engine_and_values() -> None:
    frame = pd.DataFrame([*engine_rows(), IMPORTED])
    shown = titles(drawn(level_plots.work_precision(frame, "closed form"), "work-precision"))
    expected = []
    for _, run in frame.iterrows():
        for level, column in (("position", "error_position"), ("velocity", "error_velocity")):
            if math.isfinite(run[column]):
                expected.append((run["engine"], run["setting"], level, f"{run[column]:.3g}"))
        expected.append((run["engine"], run["setting"], "acceleration", f"{run['error_acceleration']:.3g}"))
    assert len(shown) == len(expected) == 6 * 3 - 2 + 3
    for engine, setting, level, error in expected:
        assert (
            sum(
                t.startswith(f"{engine} {setting} on slider_crank") and f"{level} error {error}," in t
                for t in shown
            )
            == 1
        )
    assert sum("imported: no run time" in t for t in shown) == 3  # once per level
    assert any("run time 0.03 s" in t for t in shown)


def test_an_imported_row_does_not_move_the_run_time_axis() -> None:
    without = level_plots.work_precision(pd.DataFrame(engine_rows()), "closed form")
    with_imported = level_plots.work_precision(pd.DataFrame([*engine_rows(), IMPORTED]), "closed form")
    assert without is not None and with_imported is not None
    for plain, imported in zip(without.axes[:3], with_imported.axes[:3], strict=True):
        assert imported.get_ylim() == pytest.approx(plain.get_ylim(), rel=1e-12)
        low, high = imported.get_ylim()
        assert 0.01 < low < 0.02 and 0.05 < high < 0.1  # the timed runs' span, not the 60 s limit
    labels = [text.get_text() for text in with_imported.legends[0].get_texts()]
    assert level_plots.IMPORTED in labels
    assert level_plots.IMPORTED not in [t.get_text() for t in without.legends[0].get_texts()]


def test_a_narrow_run_time_axis_has_at_least_two_tick_labels() -> None:
    figure = level_plots.work_precision(pd.DataFrame(engine_rows()), "closed form")
    assert figure is not None
    axes = figure.axes[0]
    low, high = axes.get_ylim()
    assert math.log10(high / low) < 1  # the case of the issue: under a decade
    figure.canvas.draw()
    labelled = [
        label.get_text() for tick, label in zip(axes.get_yticks(), axes.get_yticklabels(), strict=True)
        if low <= tick <= high and label.get_text()
    ]  # fmt: skip
    assert labelled == ["2e-02", "5e-02"]  # 1, 2 and 5 of each decade within 0.0167 to 0.0758


def test_the_overview_points_have_hover_titles() -> None:
    frame = pd.DataFrame([*engine_rows(), IMPORTED])
    summary = overview.summary(frame, timeout=60.0)
    shown = titles(drawn(overview.overview_figure(summary, "closed form"), "overview"))
    assert len(shown) == 3 * 4 + 2 * 2  # newton: 4 points at 3 levels; RK4: 2 points at 2 levels
    assert not any("my_tool" in t for t in shown)  # imported rows are not summarised on a time axis
    assert all(t.startswith(("reference newton, step", "mujoco RK4, step")) for t in shown)


def test_settings_sort_by_their_numeric_value() -> None:
    shown = table(pd.DataFrame(engine_rows()))
    settings = list(shown["setting"])
    assert settings[:2] == ["RK4 dt=0.0001", "RK4 dt=0.001"]
    assert settings[2:] == [f"newton tolerance={t:g}" for t in sorted(TOLERANCES)]


def test_a_line_without_markers_has_one_title_for_the_whole_line() -> None:
    figure, axes = plt.subplots()
    (line,) = axes.plot([0.0, 1.0, 2.0], [1.0, 3.0, 2.0])
    svg_figure.hover(line, ["reference default run: largest 3"])
    assert titles(svg_figure.svg(figure, "a line")) == ["reference default run: largest 3"]


def test_texts_name_their_fonts_briefly_and_carry_no_null_rotation() -> None:
    """matplotlib writes ten fallback fonts and a rotate(0 x y) on every text; the page holds
    about 1500 texts, so the figure keeps DejaVu Sans (its layout font) and three fallbacks."""
    figure, axes = plt.subplots()
    axes.plot([1, 2], [3, 4])
    axes.set_title("a title")
    axes.set_ylabel("a turned label")
    text = svg_figure.svg(figure, "fonts")
    assert "Bitstream Vera Sans" not in text and "rotate(0 " not in text and "rotate(-0 " not in text
    root = ElementTree.fromstring(text)
    texts = [t for t in root.iter("{http://www.w3.org/2000/svg}text")]
    assert texts and all(svg_figure.FONTS in (t.get("style") or "") for t in texts)
    assert any("rotate(-90" in (t.get("transform") or "") for t in texts)  # a real turn is kept
