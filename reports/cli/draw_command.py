"""`mbxval draw SCENARIO --out fig.svg`: the mechanism drawn at a time t, or one cycle animated
(reports.drawing.drawing), as one self-contained SVG.

Everything is checked before anything is written: the output path, the scenario, t within [0,
t_end], the frame count; the file is written whole or not at all (the atomic writer).
"""

from __future__ import annotations

import argparse
from collections.abc import Callable

from reports.cli.usage import UsageError, pairs, scenario_argument
from reports.drawing import MAX_FRAMES, DrawingError, draw_svg
from reports.store import output_target, write_text
from scenarios import load


def _frames(text: str) -> int:
    """--frames: 1 (a still) or 2 to MAX_FRAMES (an animation over one cycle)."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"must be a whole number in [1, {MAX_FRAMES}], got '{text}'"
        ) from None
    if not 1 <= value <= MAX_FRAMES:
        raise argparse.ArgumentTypeError(f"must be in [1, {MAX_FRAMES}], got {value}")
    return value


def cmd_draw(args: argparse.Namespace) -> int:
    if not str(args.out).endswith(".svg"):
        raise UsageError(f"--out must name an .svg file, got '{args.out}'")
    output_target(args.out)  # a directory, device or missing folder is refused before solving
    scenario = load(args.scenario, pairs(args.set, "--set"))
    if args.t is not None and args.frames > 1:
        raise UsageError("--t draws one instant; an animation (--frames 2 or more) spans one cycle")
    t = 0.0 if args.t is None else args.t
    try:
        text = draw_svg(scenario, t, args.frames)
    except DrawingError as error:
        raise UsageError(f"{scenario.name}: {error}") from None
    write_text(args.out, text)
    print(f"wrote {args.out}")
    return 0


def add_parser(sub: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    """Add `draw` to the command line."""
    draw = sub.add_parser("draw", help="draw the mechanism as SVG, at a time or animated over a cycle")
    scenario_argument(draw)
    draw.add_argument("--out", required=True, help="SVG file to write")
    draw.add_argument("--t", type=float, help="time to draw, in [0, t_end] s (default 0)")
    draw.add_argument(
        "--frames",
        type=_frames,
        default=1,
        help=f"1: a still (default); 2 to {MAX_FRAMES}: one cycle animated in that many frames",
    )


COMMANDS: dict[str, Callable[[argparse.Namespace], int]] = {"draw": cmd_draw}
