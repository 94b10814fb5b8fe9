"""The swept stability map as a report section (reports.render.swept_map gives the data).

One heat map per sweep and engine: the first swept parameter across, the second up (a third and
further ones make one figure per combination of their values); an ok cell is coloured by its log10
error from green to red as on the first screen, any other verdict by its own colour, and the
points where the native solver detected a singular configuration carry a cross on every panel.
"""

from __future__ import annotations

import itertools
import math
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from matplotlib.axes import Axes
from matplotlib.colors import Normalize, to_rgba
from matplotlib.figure import Figure
from matplotlib.patches import Patch

import reports.render.markup as markup
import reports.render.plots as plots
import reports.render.svg_figure as svg_figure
from reports.render.first_screen import BEST, WORST
from reports.render.markdown_table import markdown_table
from reports.render.report_data import ReportData, number
from reports.render.swept_map import SweptMap, Value, swept_maps

ERRORS = plt.get_cmap("RdYlGn_r")
VERDICT_COLOURS = {
    "picked a branch": "#2166ac",
    "wrong branch": "#7b3294",
    "drifted": "#c51b7d",
    "diverged": "#111111",
    "singular detected": "#7f7f7f",
    "failed to converge": "#3b3b3b",
    "failed": "#3b3b3b",
    "timeout": "#5b3a1a",
    "unsupported": "#ffffff",
}
OTHER_VERDICT = "#3b3b3b"
"""The colour of a verdict without one of its own (failures alike; one a run never stores, such as
a store edited by hand: its text still names it in the legend)."""
MAX_FIGURES = 6
"""Combinations of the third and further swept parameters drawn, at most, per sweep."""
LEGEND = (
    f"Each cell: the engine's default setting at that point. Ok cells coloured by log10 headline error, "
    f"1e{BEST:.0f} green to 1e{WORST:.0f} red; other colours: the verdict (legend; see the stability "
    "map's verdicts). Crosses: points where the native solver detected a singular configuration."
)


def _label(value: Value) -> str:
    return f"{value:.3g}" if isinstance(value, float) else str(value)


def _ticks(values: tuple[Value, ...]) -> tuple[list[int], list[str]]:
    step = max(1, math.ceil(len(values) / 10))
    shown = list(range(0, len(values), step))
    return shown, [_label(values[k]) for k in shown]


def _image(swept: SweptMap, engine: str, fixed: dict[int, int]) -> tuple[np.ndarray, set[str]]:
    """RGBA cells of one engine's panel (rows: the second axis), and the verdicts drawn."""
    nx = len(swept.values[0])
    ny = len(swept.values[1]) if len(swept.axes) > 1 else 1
    image = np.ones((ny, nx, 4))
    image[..., :3] = 0.93  # a point without a row: light grey
    norm, seen = Normalize(BEST, WORST), set()
    for cell in swept.cells:
        if cell.engine != engine or any(cell.index[k] != v for k, v in fixed.items()):
            continue
        y = cell.index[1] if len(swept.axes) > 1 else 0
        if cell.verdict == "ok" and math.isfinite(cell.error):
            image[y, cell.index[0]] = ERRORS(norm(math.log10(max(cell.error, plots.FLOOR))))
        else:
            image[y, cell.index[0]] = to_rgba(VERDICT_COLOURS.get(cell.verdict, OTHER_VERDICT))
            seen.add(cell.verdict)
    return image, seen


def _hover_cells(axes: Axes, swept: SweptMap, engine: str, fixed: dict[int, int]) -> None:
    """An invisible square on every cell of the panel whose hover title gives the swept values, the
    verdict and the error (the colours alone do not say them)."""
    cells = [c for c in swept.cells if c.engine == engine and all(c.index[k] == v for k, v in fixed.items())]
    if not cells:
        return
    xs = [c.index[0] for c in cells]
    ys = [c.index[1] if len(swept.axes) > 1 else 0 for c in cells]
    (squares,) = axes.plot(xs, ys, ls="", marker="s", ms=6, alpha=0.0)
    titles = []
    for cell in cells:
        where = ", ".join(
            f"{name}={_label(swept.values[k][i])}"
            for k, (name, i) in enumerate(zip(swept.axes, cell.index, strict=True))
        )
        error = f", error {plots.value_text(cell.error)}" if math.isfinite(cell.error) else ""
        titles.append(f"{engine} on {swept.base} at {where}: {cell.verdict}{error}")
    svg_figure.hover(squares, titles)


def figure(swept: SweptMap, fixed: dict[int, int]) -> Figure:
    """One panel per engine; `fixed` holds the value index of each axis beyond the second."""
    nx = len(swept.values[0])
    ny = len(swept.values[1]) if len(swept.axes) > 1 else 1
    width, height = min(16.0, max(6.0, 0.18 * nx + 2.5)), max(1.3, 0.28 * ny + 0.9)
    fig, axes_list = plt.subplots(
        len(swept.engines), 1, figsize=(width, height * len(swept.engines) + 0.8), squeeze=False
    )
    singular = [i for i in swept.native_singular() if all(i[k] == v for k, v in fixed.items())]
    seen: set[str] = set()
    for axes, engine in zip(axes_list[:, 0], swept.engines, strict=True):
        image, drawn = _image(swept, engine, fixed)
        seen |= drawn
        axes.imshow(image, origin="lower", aspect="auto", interpolation="nearest")
        _hover_cells(axes, swept, engine, fixed)
        if singular:
            xs = [i[0] for i in singular]
            ys = [i[1] if len(swept.axes) > 1 else 0 for i in singular]
            axes.scatter(xs, ys, marker="x", s=40, c="#00c8ff", linewidths=1.6, zorder=3)
        axes.set_title(markup.figure_text(engine), fontsize=9, loc="left")
        axes.set_xticks(*_ticks(swept.values[0]), fontsize=7)
        if len(swept.axes) > 1:
            axes.set_yticks(*_ticks(swept.values[1]), fontsize=7)
            axes.set_ylabel(swept.axes[1], fontsize=8)
        else:
            axes.set_yticks([])
    axes_list[-1, 0].set_xlabel(swept.axes[0], fontsize=8)
    handles: list[Any] = [
        Patch(
            facecolor=VERDICT_COLOURS.get(v, OTHER_VERDICT),
            edgecolor="#999",
            label=markup.figure_text(v[:40]),
        )
        for v in sorted(seen)
    ]
    if singular:
        handles.append(plt.Line2D([], [], marker="x", ls="", color="#00c8ff", label="native singular"))
    if handles:
        fig.legend(handles=handles, loc="lower center", ncol=min(5, len(handles)), fontsize=7, frameon=False)
    bottom = 0.12 + 0.25 / len(swept.engines)
    fig.subplots_adjust(bottom=bottom, top=0.93, right=0.86, hspace=0.55)
    scale = plt.cm.ScalarMappable(Normalize(BEST, WORST), ERRORS)
    fig.colorbar(scale, cax=fig.add_axes((0.88, bottom, 0.015, 0.93 - bottom)), label="log10 error (ok runs)")
    return fig


def combinations(swept: SweptMap) -> list[dict[int, int]]:
    """Value indices of the third and further axes, one dict per figure (at most MAX_FIGURES)."""
    extra = range(2, len(swept.axes))
    every = itertools.product(*(range(len(swept.values[k])) for k in extra))
    return [dict(zip(extra, combo, strict=True)) for combo in itertools.islice(every, MAX_FIGURES)]


def _title(swept: SweptMap, fixed: dict[int, int]) -> str:
    where = ", ".join(f"{swept.axes[k]}={_label(swept.values[k][v])}" for k, v in fixed.items())
    return f"{swept.base} over {' × '.join(swept.axes[:2])}" + (f" at {where}" if where else "")


def _summary(swept: SweptMap) -> str:
    points = len({c.point for c in swept.cells})
    shape = " × ".join(str(len(v)) for v in swept.values)
    singular = sorted(swept.native_singular())
    where = ", ".join(
        "(" + ", ".join(_label(swept.values[k][i]) for k, i in enumerate(index)) + ")"
        for index in singular[:8]
    )
    more = f" and {len(singular) - 8} more" if len(singular) > 8 else ""
    text = f"{points} points ({shape}) on {', '.join(swept.engines)}."
    return text + (f" Native solver singular at {where}{more}." if singular else " No native singular point.")


def html_fragment(data: ReportData) -> str:
    """The swept maps' section, or "" when the results hold no sweep."""
    maps = swept_maps(data)
    if not maps:
        return ""
    parts = ["<h2>Stability over the swept parameters</h2>", f'<p class="muted">{markup.escape(LEGEND)}</p>']
    for swept in maps:
        parts.append(f"<p><strong>{markup.escape(swept.base)}</strong>: {markup.escape(_summary(swept))}</p>")
        for fixed in combinations(swept):
            title = _title(swept, fixed)
            image = svg_figure.svg(figure(swept, fixed), title)
            parts.append(f'<p class="muted">{markup.escape(title)}</p>{image}')
    return "\n".join(parts)


def markdown_section(data: ReportData) -> str:
    """Each sweep as a table: one row per point, one column per engine (verdict and error)."""
    maps = swept_maps(data)
    if not maps:
        return ""
    lines = ["## Stability over the swept parameters", "", LEGEND]
    for swept in maps:
        table: dict[str, dict[str, Any]] = {}
        for cell in sorted(swept.cells, key=lambda c: c.index):
            text = cell.verdict + (f" {number(cell.error)}" if math.isfinite(cell.error) else "")
            text += f" @{cell.time:.4g} s" if math.isfinite(cell.time) else ""
            table.setdefault(cell.point, {})[cell.engine] = text
        frame = _frame(table, swept.engines)
        lines += ["", f"### {markup.markdown_text(swept.base)}", "", markup.markdown_text(_summary(swept))]
        lines += ["", markdown_table(frame, "point")]
    return "\n".join(lines) + "\n"


def _frame(table: dict[str, dict[str, Any]], engines: tuple[str, ...]) -> Any:

    return pd.DataFrame(
        [{e: cells.get(e, "") for e in engines} for cells in table.values()], index=list(table)
    )
