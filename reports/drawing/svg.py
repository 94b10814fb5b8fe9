"""A mechanism drawing as one self-contained SVG: the shapes of reports.drawing.geometry
mapped to the page (equal axes, world y up), labelled, with a scale bar in metres and a title; with
several instants, one frame each, played in a loop by SMIL (no script).

The page coordinates of a world point (x, y) are (ox + s x, oy - s y), with s, ox and oy written on
the root element as `data-scale`, `data-origin-x` and `data-origin-y`, so a reader can map any drawn
point back to metres.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from xml.sax.saxutils import escape, quoteattr

import numpy as np

from reports.drawing.geometry import Instant, Shape
from reports.drawing.labels import FONT_SIZE, Box, place

WIDTH = 900.0
MAX_HEIGHT = 700.0
MARGIN = 60.0
TOP = 46.0
BOTTOM = 40.0
PIN = 5.0
"""A pin's radius in pixels (pins, pivots and arrows keep their size on the page at any scale)."""
PIN_SPACING = 90.0
"""Pins are drawn this many pixels apart at least, typically (the page grows, up to LARGEST pixels)."""
LARGEST = 6000.0
CHAIN_PINS = 8
"""Pin places from which a mechanism is a chain whose pins are kept PIN_SPACING apart."""
SMALLEST = 4.0
"""A circle is drawn at least this many pixels in radius, so that a small gear stays visible."""
PALETTE = ("#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf", "#8c564b", "#e377c2")
CIRCLES = {"gear", "ring", "roller", "disc"}
STYLE = """
text{font-family:sans-serif;fill:#222}
.label{font-size:12px}
.title{font-size:16px;font-weight:bold}
.sub{font-size:12px;fill:#555}
.bar{stroke-width:9;stroke-linecap:round;fill:none;opacity:.85}
.plate{stroke-width:5;stroke-linejoin:round;fill-opacity:.3}
.block{stroke-width:1.5;fill-opacity:.75;stroke:#222}
.disc,.cam{stroke-width:2;fill-opacity:.25}
.gear,.ring{stroke-width:2.5;stroke-dasharray:10 3 2 3;fill-opacity:.12}
.ring{stroke-width:5;fill:none}
.spoke{stroke-width:2;fill:none}
.rack{stroke-width:6;stroke-linecap:butt}
.teeth{stroke-width:14;stroke-dasharray:3 7;fill:none}
.stem,.face{stroke-width:6;stroke-linecap:round;fill:none}
.knife{stroke:#222;stroke-width:1}
.roller{stroke-width:2.5;fill:#fff}
.contact{fill:#d62728;stroke:none}
.mesh{fill:#fff;stroke:#d62728;stroke-width:1.5}
.revolute{fill:#fff;stroke:#222;stroke-width:2}
.support{fill:#fff;stroke:#222;stroke-width:1.5}
.guide{stroke:#444;stroke-width:1.5;stroke-dasharray:6 4;fill:none}
.ground{stroke:#222;stroke-width:1.5;fill:none}
.hatch{fill:url(#hatch);stroke:none}
.driver{stroke:#e6550d;stroke-width:2;fill:none}
.load{stroke:#6a3d9a;stroke-width:2;fill:none}
.spring{stroke:#555;stroke-width:1.5;fill:none}
.scale{stroke:#222;stroke-width:2;fill:none}
"""
SCOPE = "mechanism-drawing"
"""The root's class: every style rule is scoped under it, so that drawings inline in a page neither
take nor give styles."""


def scoped_style(ids: str) -> str:
    """STYLE with each rule under the root's class, its pattern named with the drawing's `ids`."""
    rules = []
    for line in STYLE.strip().splitlines():
        selectors, _, body = line.partition("{")
        scoped = ",".join(f".{SCOPE} {sel}" for sel in selectors.split(","))
        rules.append(scoped + "{" + body.replace("#hatch", f"#{ids}-hatch"))
    return "\n".join(rules)


def unique_ids(text: str, ids: str) -> str:
    """The drawing's marker and pattern named with `ids`, so that several drawings can sit inline in
    one page without their ids clashing."""
    for name in ("hatch", "arrow"):
        text = text.replace(f'id="{name}"', f'id="{ids}-{name}"').replace(
            f"url(#{name})", f"url(#{ids}-{name})"
        )
    return text


DEFS = """<defs>
<pattern id="hatch" width="6" height="6" patternUnits="userSpaceOnUse" patternTransform="rotate(45)">
<line x1="0" y1="0" x2="0" y2="6" stroke="#222" stroke-width="1.5"/></pattern>
<marker id="arrow" viewBox="0 0 10 10" refX="8" refY="5" markerWidth="7" markerHeight="7" \
orient="auto-start-reverse"><path d="M0,0 L10,5 L0,10 z" fill="context-stroke"/></marker>
</defs>"""


@dataclass(frozen=True)
class View:
    """The map from world metres to page pixels: (ox + s x, oy - s y)."""

    scale: float
    ox: float
    oy: float
    width: float
    height: float

    def at(self, p: tuple[float, float]) -> tuple[float, float]:
        return (self.ox + self.scale * p[0], self.oy - self.scale * p[1])


def num(v: float) -> str:
    """A page coordinate: 7 decimals (1e-7 px), trailing zeros dropped."""
    text = f"{v:.7f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def fit(instants: Sequence[Instant], size: float) -> View:
    """Equal axes fitted to every instant's shapes with a margin (at least `size` wide and high)."""
    xs: list[float] = []
    ys: list[float] = []
    for shape in (s for i in instants for s in i.shapes):
        points = shape.points[::2] if shape.kind == "ground_guide" else shape.points
        r = shape.radius if shape.kind in CIRCLES else 0.0
        for x, y in points:
            xs += [x - r, x + r]
            ys += [y - r, y + r]
    x0, x1, y0, y1 = min(xs), max(xs), min(ys), max(ys)
    grow_x, grow_y = max(size - (x1 - x0), 0.0) / 2, max(size - (y1 - y0), 0.0) / 2
    x0, x1, y0, y1 = x0 - grow_x, x1 + grow_x, y0 - grow_y, y1 + grow_y
    inner_w, inner_h = WIDTH - 2 * MARGIN, MAX_HEIGHT - TOP - BOTTOM - 2 * MARGIN
    scale = min(inner_w / (x1 - x0), inner_h / (y1 - y0))
    crowded = min(PIN_SPACING / _typical_pin_gap(instants[0]), (LARGEST - 2 * MARGIN) / max(x1 - x0, y1 - y0))
    scale = max(scale, crowded)  # a long chain of small loops: a larger page, so labels fit
    width = max(WIDTH, 2 * MARGIN + scale * (x1 - x0))
    height = TOP + BOTTOM + 2 * MARGIN + scale * (y1 - y0)
    ox = MARGIN + (width - 2 * MARGIN - scale * (x1 - x0)) / 2 - scale * x0
    return View(scale, ox, TOP + MARGIN + scale * y1, width, height)


def _typical_pin_gap(instant: Instant) -> float:
    """The median over the pins of the distance to the nearest other pin not at the same place
    (inf for fewer than CHAIN_PINS places): small for a long chain of small loops. A short linkage
    with one tiny link (a crank 1e-3 of its rod) is drawn to scale, its tiny link as small as it is."""
    points = np.unique(np.array([s.points[0] for s in instant.shapes if s.kind == "revolute"]), axis=0)
    if len(points) < CHAIN_PINS:
        return math.inf
    gaps = np.linalg.norm(points[:, None, :] - points[None, :, :], axis=2)
    gaps[gaps <= 1e-9 * float(np.max(gaps))] = math.inf
    return float(np.median(np.min(gaps, axis=1)))


def _colour(name: str, bodies: Sequence[str]) -> str:
    return PALETTE[bodies.index(name) % len(PALETTE)] if name in bodies else "#555"


def _line(kind: str, a: tuple[float, float], b: tuple[float, float], extra: str = "") -> str:
    return (
        f'<line class="{kind}" x1="{num(a[0])}" y1="{num(a[1])}" x2="{num(b[0])}" y2="{num(b[1])}"{extra}/>'
    )


def _polygon(kind: str, points: Sequence[tuple[float, float]], extra: str = "", closed: bool = True) -> str:
    """Outlines to 0.01 px (a cam's profile has hundreds of points in every frame); pins, whose
    places are read back, keep num's precision."""
    tag = "polygon" if closed else "polyline"
    text = " ".join(f"{x:.2f},{y:.2f}" for x, y in points)
    return f'<{tag} class="{kind}" points="{text}"{extra}/>'


def _circle(kind: str, c: tuple[float, float], r: float, extra: str = "") -> str:
    return f'<circle class="{kind}" cx="{num(c[0])}" cy="{num(c[1])}" r="{num(r)}"{extra}/>'


def _arc(kind: str, c: tuple[float, float], sense: float, radius: float = 22.0) -> str:
    """A 260-degree arc about c with its arrow heads on the sense of rotation (both for 0)."""
    start, end = math.radians(-50.0), math.radians(210.0)
    p0 = (c[0] + radius * math.cos(start), c[1] - radius * math.sin(start))
    p1 = (c[0] + radius * math.cos(end), c[1] - radius * math.sin(end))
    heads = {1.0: ' marker-end="url(#arrow)"', -1.0: ' marker-start="url(#arrow)"'}
    marks = heads.get(sense, ' marker-start="url(#arrow)" marker-end="url(#arrow)"')
    d = f"M{num(p0[0])},{num(p0[1])} A{radius},{radius} 0 1 0 {num(p1[0])},{num(p1[1])}"
    return f'<path class="{kind}" d="{d}"{marks}/>'


def _clip(view: View, base: tuple[float, float], u: tuple[float, float]) -> tuple[tuple[float, float], ...]:
    """The page segment of the line through `base` along `u` (page units) inside the margin."""
    lo_x, hi_x, lo_y, hi_y = MARGIN / 3, view.width - MARGIN / 3, TOP + MARGIN / 3, view.height - BOTTOM
    ts = []
    for p, d, lo, hi in ((base[0], u[0], lo_x, hi_x), (base[1], u[1], lo_y, hi_y)):
        if abs(d) > 1e-12:
            ts.append(sorted(((lo - p) / d, (hi - p) / d)))
    t0 = max(t[0] for t in ts)
    t1 = min(t[1] for t in ts)
    return ((base[0] + t0 * u[0], base[1] + t0 * u[1]), (base[0] + t1 * u[0], base[1] + t1 * u[1]))


def _zigzag(a: tuple[float, float], b: tuple[float, float]) -> list[tuple[float, float]]:
    length = math.dist(a, b) or 1.0
    u = ((b[0] - a[0]) / length, (b[1] - a[1]) / length)
    n = (-u[1], u[0])
    points = [a]
    for k in range(13):
        s = 0.2 + 0.6 * k / 12
        side = 0.0 if k in (0, 12) else (6.0 if k % 2 else -6.0)
        points.append((a[0] + s * length * u[0] + side * n[0], a[1] + s * length * u[1] + side * n[1]))
    return [*points, b]


def element(shape: Shape, view: View, colour: str) -> str:
    """The SVG of one shape, with its hover title: one branch per shape kind (a dispatch table of
    small renderers would spread the page's geometry over a dozen functions of three lines)."""
    pts = [view.at(p) for p in shape.points]
    paint = f' stroke="{colour}" fill="{colour}"'
    kind, title = shape.kind, f"<title>{escape(shape.title)}</title>" if shape.title else ""
    if kind in CIRCLES:
        r = max(shape.radius * view.scale, SMALLEST)
        body = _circle(kind, pts[0], r, f" stroke={quoteattr(colour)}" if kind == "roller" else paint)
    elif kind in ("bar", "stem", "face", "spoke"):
        body = _polygon(kind, pts, f' stroke="{colour}"', closed=False)
    elif kind in ("plate", "block", "cam", "knife"):
        body = _polygon(kind, pts, paint if kind != "knife" else ' fill="#444"')
    elif kind == "rack":
        body = _line(kind, pts[0], pts[1], f' stroke="{colour}"') + _line(
            "teeth", pts[0], pts[1], f' stroke="{colour}"'
        )
    elif kind == "revolute":
        body = _circle("revolute", pts[0], PIN, f" data-joint={quoteattr(shape.name)}")
    elif kind in ("contact", "mesh"):
        body = _circle(kind, pts[0], 3.5)
    elif kind == "ground_pivot":
        x, y = pts[0]
        body = _polygon("support", [(x, y), (x - 11, y + 17), (x + 11, y + 17)])
        body += f'<rect class="hatch" x="{num(x - 17)}" y="{num(y + 17)}" width="34" height="7"/>'
        body += _line("ground", (x - 17, y + 17), (x + 17, y + 17))
    elif kind == "anchor":
        x, y = pts[0]
        body = f'<rect class="hatch" x="{num(x - 9)}" y="{num(y)}" width="18" height="7"/>'
        body += _line("ground", (x - 9, y), (x + 9, y))
    elif kind == "sleeve":
        a, b = pts
        length = math.dist(a, b) or 1.0
        n = ((b[1] - a[1]) / length, -(b[0] - a[0]) / length)
        body = ""
        for side in (9.0, -9.0):
            near = [(p[0] + side * n[0], p[1] + side * n[1]) for p in (a, b)]
            far = [(p[0] + 1.8 * side * n[0], p[1] + 1.8 * side * n[1]) for p in (a, b)]
            body += _polygon("hatch", [near[0], near[1], far[1], far[0]]) + _line("ground", near[0], near[1])
    elif kind in ("ground_guide", "guide"):
        if kind == "guide":
            body = _line("guide", pts[0], pts[1])
        else:
            u = (pts[1][0] - pts[0][0], pts[1][1] - pts[0][1])  # pts[2]: the slider, for the label
            a, b = _clip(view, pts[0], u)
            length = math.dist(a, b) or 1.0
            n = ((b[1] - a[1]) / length, -(b[0] - a[0]) / length)
            if n[1] < 0 or (n[1] == 0 and n[0] < 0):
                n = (-n[0], -n[1])
            far = [(a[0] + 7 * n[0], a[1] + 7 * n[1]), (b[0] + 7 * n[0], b[1] + 7 * n[1])]
            body = _polygon("hatch", [a, b, far[1], far[0]]) + _line("ground", a, b)
    elif kind in ("driver_arc", "torque"):
        body = _arc("driver" if kind == "driver_arc" else "load", pts[0], shape.value)
    elif kind in ("driver_line", "force"):
        a, b = pts
        length = math.dist(a, b)
        if length < 36.0:
            u = ((b[0] - a[0]) / (length or 1.0), (b[1] - a[1]) / (length or 1.0))
            b = (a[0] + 36.0 * u[0], a[1] + 36.0 * u[1])
        heads = ' marker-end="url(#arrow)"' + ("" if shape.value else ' marker-start="url(#arrow)"')
        body = _line("driver" if kind == "driver_line" else "load", a, b, heads)
    elif kind == "driver_point":
        body = _circle("driver", pts[0], 10.0, ' stroke-dasharray="4 3"')
    elif kind == "spring":
        body = _polygon("spring", _zigzag(*pts), closed=False)
    else:
        raise ValueError(f"unknown shape kind '{kind}'")
    return f"<g data-name={quoteattr(shape.name)}>{title}{body}</g>"


def anchor(shape: Shape, view: View) -> tuple[tuple[float, float], float]:
    """Where a shape's label is attached on the page, and how far from it the label keeps."""
    pts = [view.at(p) for p in shape.points]
    if shape.kind in CIRCLES:
        r = max(shape.radius * view.scale, SMALLEST)
        return (pts[0][0] + 0.7 * r, pts[0][1] - 0.7 * r), 4.0
    if shape.kind in ("revolute", "contact", "mesh", "ground_pivot"):
        return pts[0], PIN + 2
    if shape.kind in ("driver_arc", "torque"):
        return pts[0], 26.0
    if shape.kind == "ground_guide":
        return pts[2], 14.0
    if shape.kind == "cam":  # its top-left, away from the pivot at its centre
        return min(pts, key=lambda p: p[0] + p[1]), 4.0
    if shape.kind == "sleeve":
        return pts[1], 16.0
    if shape.kind in ("driver_line", "force"):
        return pts[-1], 6.0
    return (sum(p[0] for p in pts) / len(pts), sum(p[1] for p in pts) / len(pts)), 8.0


def frame(instant: Instant, view: View, bodies: Sequence[str]) -> str:
    """One instant's shapes, then their labels (each name once), clear of pins and each other."""
    parts = [element(s, view, _colour(s.name, bodies)) for s in instant.shapes]
    pins: list[Box] = []
    wanted: dict[str, tuple[str, tuple[float, float], float]] = {}
    for s in instant.shapes:
        if s.kind == "revolute":
            x, y = view.at(s.points[0])
            pins.append((x - PIN - 1, y - PIN - 1, x + PIN + 1, y + PIN + 1))
        if s.label and s.label not in wanted:
            wanted[s.label] = (s.label, *anchor(s, view))
    canvas = (4.0, TOP, view.width - 4.0, view.height - BOTTOM + FONT_SIZE)
    ordered = sorted(wanted.values(), key=lambda w: w[2])  # pins and small things first
    labels = [
        f'<text class="label" x="{num(p.x)}" y="{num(p.y)}">{escape(p.text)}</text>'
        for p in place(ordered, pins, canvas)
    ]
    return "\n".join(parts + labels)
