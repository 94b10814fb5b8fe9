"""Each scenario of a run drawn and left beside its results (DIR/drawings/), so that the report
shows the mechanism without drawing it (reports.render.drawings reads them): one cycle in
REPORT_FRAMES frames where that animation stays small, else the still at t = 0."""

from __future__ import annotations

import hashlib
import json
import warnings
from collections.abc import Iterable
from pathlib import Path

from reports.drawing.drawing import DrawingError, draw_svg
from reports.render import DRAWINGS, INDEX, read_index
from reports.store import atomic_output
from scenarios import Scenario
from scenarios.names import safe_file_stem

MAX_BODIES = 30
"""A scenario with more bodies is not drawn for the report (n_four_bar/spec's 81 take about a
minute to pose); `mbxval draw` still draws it."""
REPORT_FRAMES = 12
"""Frames of the report's animation of one cycle (`mbxval draw --frames` draws any number)."""
MAX_ANIMATION_BYTES = 48_000
"""An animation larger than this is left out for the still: the page carries every drawing, and
a cam's twelve redrawn profiles (about 90 to 130 kB) would add more than its figures."""


def file_name(scenario: str) -> str:
    """A file name for a scenario's drawing: its name's letters, and a digest that keeps names
    that differ only in other characters apart (a scenario's name holds '/' and brackets: it is
    encoded, then passes the one check of every name that becomes a file name)."""
    plain = "".join(c if c.isascii() and c.isalnum() else "_" for c in scenario)[:60]
    stem = f"{plain}-{hashlib.sha256(scenario.encode()).hexdigest()[:10]}"
    return f"{safe_file_stem(stem, 'a drawing')}.svg"


def write_drawings(out: Path, scenarios: Iterable[Scenario]) -> dict[str, str]:
    """Draw each scenario (report_drawing) into out/drawings/ and add them to its index (the drawings of
    earlier runs into `out` stay); a scenario that cannot be drawn is left out with a warning, never
    failing the run. Returns the index, {scenario: file name}."""
    folder = out / DRAWINGS
    folder.mkdir(exist_ok=True)
    index = read_index(folder)
    for scenario in scenarios:
        if len(scenario.bodies) > MAX_BODIES:
            continue
        try:
            text = report_drawing(scenario)
        except Exception as error:  # a picture is never worth a run: say why and go on
            warnings.warn(f"{scenario.name}: not drawn ({error})", RuntimeWarning, stacklevel=2)
            continue
        name = file_name(scenario.name)
        with atomic_output(folder / name) as stream:
            stream.write(text)
        index[scenario.name] = name
    with atomic_output(folder / INDEX) as stream:
        stream.write(json.dumps(index, indent=1, sort_keys=True))
    return index


def report_drawing(scenario: Scenario) -> str:
    """The scenario's cycle in REPORT_FRAMES frames when that fits MAX_ANIMATION_BYTES, else its
    still at t = 0 (also where no cycle can be animated)."""
    still = draw_svg(scenario)
    try:
        animation = draw_svg(scenario, frames=REPORT_FRAMES)
    except DrawingError:
        return still
    return animation if len(animation.encode("utf-8")) <= MAX_ANIMATION_BYTES else still
