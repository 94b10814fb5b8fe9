"""What every figure of the report shares: engine colours, markers, the floor of log axes, and the
rows without a run time, and a setting's swept value (the figures: reports.render.level_plots,
overview; drawn as SVG by reports.render.svg_figure)."""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any

import numpy as np
import pandas as pd
from matplotlib.axes import Axes
from matplotlib.colors import is_color_like

from reports.render.markup import figure_text

FLOOR = 1e-17  # errors of exactly zero are drawn here on log axes
MARKERS = "osD^v<>p*h"
PALETTE = ("#9467bd", "#8c564b", "#e377c2", "#bcbd22", "#17becf", "#ff7f0e")
"""The colours of a name the store gives none (an engine that declares none, an imported
trajectory's label, a store from before colours were stored), chosen by the name so that it keeps
its colour from one report to the next."""
_STORED: dict[str, str] = {}


def use_stored_colours(colours: object) -> None:
    """Draw each engine in the colour its store records (the sidecar's `engine_colours`, which the
    run took from the engine's adapter); ReportData.load calls it. A colour matplotlib cannot draw,
    or a sidecar entry that is no mapping (a store edited by hand), leaves the palette's."""
    _STORED.clear()
    if isinstance(colours, Mapping):
        _STORED.update({str(k): v for k, v in colours.items() if isinstance(v, str) and is_color_like(v)})


def colour(engine: str) -> str:
    """The colour `engine`'s rows are drawn in: as stored, else one of PALETTE by its name."""
    return _STORED.get(engine) or PALETTE[sum(map(ord, engine)) % len(PALETTE)]


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


def untimed(frame: pd.DataFrame) -> pd.Series:
    """The rows that ended ok without a run time (imported trajectories, `mbxval compare`): drawn
    in a strip of their own, off every time axis and its limits."""
    times = pd.to_numeric(frame["run_time"], errors="coerce") if "run_time" in frame else np.nan
    return (frame["status"] == "ok") & ~np.isfinite(pd.Series(times, index=frame.index, dtype=float))


def swept_value(setting: str) -> str:
    """The first value a setting label sets, numbers to three digits (`RK4 dt=6.28319e-05 tc=0.1`
    gives `dt=6.28e-05`); the mode itself for a setting without values."""
    parts = str(setting).split(" ")
    first = next((p for p in parts[1:] if "=" in p), parts[0])
    key, _, value = first.partition("=")
    try:
        return f"{key}={float(value):.3g}"
    except ValueError:
        return first


def value_text(value: float) -> str:
    return "0" if value == 0 else f"{value:.3g}"
