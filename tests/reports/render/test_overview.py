"""The suite overview's summary: shifted geometric means over scenarios, per engine-mode ladder rung."""

from __future__ import annotations

import math

import pandas as pd
import pytest

from reports.render.overview import SHIFT_ERROR, overview_figure, shifted_geometric_mean, summary


def test_shifted_geometric_mean_by_hand() -> None:
    assert shifted_geometric_mean([1.0, 100.0], 0.0) == pytest.approx(10.0)
    assert shifted_geometric_mean([0.0, 0.0], 1e-15) == pytest.approx(0.0, abs=1e-25)
    assert math.isnan(shifted_geometric_mean([math.nan], 1.0))


def row(scenario: str, setting: str, status: str, error: float, time: float) -> dict[str, object]:
    return {
        "scenario": scenario, "engine": "e", "mode": setting.split(" ")[0], "setting": setting,
        "is_default": setting.endswith("dt=0.01") or setting.endswith("dt=0.1"), "status": status,
        "run_time": time, "error_position": error, "error_velocity": math.nan, "error_acceleration": error,
    }  # fmt: skip


def test_the_kth_step_is_summarised_across_scenarios_and_failures_count() -> None:
    frame = pd.DataFrame(
        [
            row("a", "RK4 dt=0.01", "ok", 1e-4, 0.01),  # a's coarsest step
            row("a", "RK4 dt=0.001", "ok", 1e-8, 0.1),
            row("b", "RK4 dt=0.1", "ok", 1e-6, 0.01),  # b's coarsest step (another period)
            row("b", "RK4 dt=0.01", "diverged", math.nan, math.nan),
        ]
    )
    table = summary(frame, timeout=10.0).set_index("rung")
    assert list(table.index) == [1, 2]
    coarse, fine = table.loc[1], table.loc[2]
    assert coarse["scenarios"] == 2 and coarse["not_ok"] == 0 and bool(coarse["default"])
    assert coarse["error_position"] == pytest.approx(
        math.sqrt((1e-4 + SHIFT_ERROR) * (1e-6 + SHIFT_ERROR)) - SHIFT_ERROR
    )
    assert fine["not_ok"] == 1  # the divergence counts as error 1 at the time limit
    assert fine["error_position"] == pytest.approx(math.sqrt((1e-8 + SHIFT_ERROR) * 1.0), rel=1e-6)
    assert fine["run_time"] == pytest.approx(math.sqrt((0.1 + 1e-3) * (10.0 + 1e-3)) - 1e-3)
    assert math.isnan(coarse["error_velocity"])  # a level the engine does not produce stays out


LONG_TRUTH = (
    "native, tolerance 1e-12 / native, tolerance 1e-12 on slider_crank, scaled / native, tolerance "
    "1e-12, grid refined 4x / closed form"
)
"""The truths of a stress run before its family cases took their closed forms: the caption that
was cut off at both edges of the figure ("ver the suite (shifted geometric mean; ...")."""


@pytest.mark.parametrize("truth", ["closed form", LONG_TRUTH, LONG_TRUTH * 4])
def test_the_caption_stays_inside_the_figure_and_clear_of_the_panels(truth: str) -> None:
    frame = pd.DataFrame(
        [row("a", "RK4 dt=0.01", "ok", 1e-4, 0.01), row("a", "RK4 dt=0.001", "ok", 1e-8, 0.1)]
    )
    figure = overview_figure(summary(frame, timeout=10.0), truth)
    assert figure is not None
    renderer = figure.canvas.get_renderer()  # type: ignore[attr-defined]
    caption = figure.get_suptitle()
    assert caption.startswith("error against run time over the suite") and caption.endswith(")")
    assert (truth in " ".join(caption.split("\n"))) == (truth != LONG_TRUTH * 4)  # too long: shortened
    box = next(t for t in figure.texts if t.get_text() == caption).get_window_extent(renderer)
    width, height = figure.bbox.width, figure.bbox.height
    assert box.x0 > 0 and box.x1 < width and box.y1 < height, (box, width, height)
    for axes in figure.axes[:3]:
        assert axes.title.get_window_extent(renderer).y1 < box.y0  # the panel titles below it
