"""Where a drawing's name labels go: beside their anchor, clear of the other labels and pins and
inside the canvas, tried in a fixed order of places (greedy, so the result is reproducible)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

FONT_SIZE = 12.0
CHAR_WIDTH = 0.6 * FONT_SIZE
"""A label's width is estimated at this many pixels per character (sans-serif, 12 px)."""

Box = tuple[float, float, float, float]
"""(left, top, right, bottom) in pixels."""


@dataclass(frozen=True)
class Placed:
    """A label's text and its baseline's left end, in pixels."""

    text: str
    x: float
    y: float


def _box(x: float, y: float, text: str) -> Box:
    return (x, y - FONT_SIZE + 2, x + CHAR_WIDTH * len(text), y + 3)


def _overlap(a: Box, b: Box) -> float:
    w = min(a[2], b[2]) - max(a[0], b[0])
    h = min(a[3], b[3]) - max(a[1], b[1])
    return max(w, 0.0) * max(h, 0.0)


def _offsets(width: float, clear: float) -> list[tuple[float, float]]:
    """Places beside an anchor, nearest first: the four diagonals, above and below, left and right,
    then the same twice as far."""
    places = []
    for k in (1.0, 2.2, 3.6):
        c = clear * k
        places += [
            (c, -c),
            (c, c + FONT_SIZE - 3),
            (-c - width, -c),
            (-c - width, c + FONT_SIZE - 3),
            (-width / 2, -c - 2),
            (-width / 2, c + FONT_SIZE),
            (c + 2, FONT_SIZE / 2 - 2),
            (-c - 2 - width, FONT_SIZE / 2 - 2),
        ]
    return places


def place(
    wanted: Sequence[tuple[str, tuple[float, float], float]],
    obstacles: Sequence[Box],
    canvas: Box,
) -> list[Placed]:
    """Each label (text, anchor in pixels, clearance from the anchor in pixels) at the first place
    that overlaps nothing placed before nor an obstacle, inside `canvas`; where none is free, the
    place that overlaps least."""
    taken: list[Box] = list(obstacles)
    placed: list[Placed] = []
    for text, (ax, ay), clear in wanted:
        width = CHAR_WIDTH * len(text)
        best: tuple[float, float, float] | None = None
        for dx, dy in _offsets(width, max(clear, 6.0)):
            x = min(max(ax + dx, canvas[0]), canvas[2] - width)
            y = min(max(ay + dy, canvas[1] + FONT_SIZE), canvas[3] - 3)
            box = _box(x, y, text)
            cost = sum(_overlap(box, other) for other in taken)
            if best is None or cost < best[0]:
                best = (cost, x, y)
            if cost == 0.0:
                break
        assert best is not None
        taken.append(_box(best[1], best[2], text))
        placed.append(Placed(text, best[1], best[2]))
    return placed
