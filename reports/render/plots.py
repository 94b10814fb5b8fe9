"""What every figure of the report shares: engine colours, markers, the floor of log axes, and the
base64 PNG encoding for a self-contained page (the figures: reports.render.level_plots, overview)."""

from __future__ import annotations

import base64
import io
from collections.abc import Iterable
from typing import Any

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from reports.render.markup import figure_text

FLOOR = 1e-17  # errors of exactly zero are drawn here on log axes
COLOURS = {"reference": "#444444", "mujoco": "#1f77b4", "exudyn": "#d62728", "pinocchio": "#2ca02c"}
OTHER_COLOURS = ("#9467bd", "#8c564b", "#e377c2", "#bcbd22", "#17becf", "#ff7f0e")
MARKERS = "osD^v<>p*h"


def colour(engine: str) -> str:
    if engine in COLOURS:
        return COLOURS[engine]
    return OTHER_COLOURS[sum(map(ord, engine)) % len(OTHER_COLOURS)]


def legend_entries(panels: Iterable[Axes]) -> tuple[list[Any], list[str]]:
    """Every labelled line of the panels, each label once, for one legend of the whole figure (the
    labels shown as written: markup.figure_text)."""
    handles: list[Any] = []
    labels: list[str] = []
    for axes in panels:
        for handle, label in zip(*axes.get_legend_handles_labels(), strict=True):
            if label not in labels:
                handles.append(handle)
                labels.append(label)
    return handles, [figure_text(label) for label in labels]


def png(figure: Figure, tight: bool = True) -> str:
    """The figure as base64 PNG text (and the figure closed); `tight` False keeps the figure's own
    margins, which saves measuring every text of a many-panel figure again."""
    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", dpi=90, bbox_inches="tight" if tight else None)
    plt.close(figure)
    return base64.b64encode(buffer.getvalue()).decode("ascii")
