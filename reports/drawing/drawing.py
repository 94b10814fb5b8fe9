"""Draw a scenario's mechanism at a time t, or as a looping animation over one cycle: one
self-contained SVG (`draw_svg`), the bodies posed by the native solver.

It solves (hence a package apart from reports.render): a drawing shows the scenario itself, not a
stored run. The native solver marches from t = 0 to t on a grid as fine as the scenario's own (so that it
follows the scenario's assembly branch), with its default setting for kinematics and a relative
tolerance of DYNAMIC_RTOL for forward dynamics (a drawing needs no more). The scenario is read,
never changed.
"""

from __future__ import annotations

import hashlib
import math
from xml.sax.saxutils import escape

import numpy as np

import adapters
from adapters.base import Setting
from reports.drawing.geometry import Instant, instant
from reports.drawing.svg import (
    BOTTOM,
    DEFS,
    MARGIN,
    SCOPE,
    View,
    fit,
    frame,
    num,
    scoped_style,
    unique_ids,
)
from reports.scoring import consistent_start
from scenarios import Scenario
from scenarios.drivers import AbsoluteDriver, RelativeRotationDriver
from scenarios.motions import ConstantSpeed, Harmonic
from scenarios.trajectory import Trajectory

MAX_FRAMES = 240
DYNAMIC_RTOL = 1e-9
"""The native integrator's relative tolerance for a dynamic scenario's drawing."""
SECONDS_PER_FRAME = 0.1
"""An animation plays one cycle in this many seconds per frame, within [2, 8] s."""


class DrawingError(ValueError):
    """A drawing that cannot be made: a time or frame count out of range, or a solve that failed."""


def cycle(scenario: Scenario) -> float:
    """One cycle of the scenario: the period of its rotating or oscillating drivers when they share
    one and it fits the horizon, otherwise the whole horizon t_end."""
    periods = set()
    for d in scenario.drivers:
        motion = d.motion if isinstance(d, AbsoluteDriver | RelativeRotationDriver) else None
        if isinstance(motion, ConstantSpeed) and motion.rate and getattr(d, "coordinate", "theta") == "theta":
            periods.add(round(2.0 * math.pi / abs(motion.rate), 12))
        elif isinstance(motion, Harmonic) and motion.omega:
            periods.add(round(2.0 * math.pi / abs(motion.omega), 12))
        else:
            return scenario.t_end
    if scenario.analysis == "dynamic" or len(periods) != 1:
        return scenario.t_end
    return min(periods.pop(), scenario.t_end)


def native_setting(scenario: Scenario) -> Setting:
    """The native solver's setting for a drawing."""
    if scenario.analysis == "dynamic":
        return Setting.of("DOP853", rtol=DYNAMIC_RTOL)
    return adapters.load(adapters.NATIVE).default_setting(scenario)


def still_grid(scenario: Scenario, t: float) -> np.ndarray:
    """The grid from 0 to t the solver marches on (at least one step: a t = 0 drawing is its
    first point), as fine as the scenario's own."""
    if not (math.isfinite(t) and 0.0 <= t <= scenario.t_end):
        raise DrawingError(f"t must be in [0, {scenario.t_end:.6g}] s (the scenario's t_end), got {t}")
    step = scenario.t_end / scenario.steps
    if t == 0.0:
        return np.array([0.0, step])
    return np.linspace(0.0, t, max(1, math.ceil(t / step - 1e-9)) + 1)


def frame_grid(scenario: Scenario, frames: int) -> tuple[np.ndarray, list[int]]:
    """The grid over one cycle and the indices of the `frames` equally spaced frames on it."""
    if not 2 <= frames <= MAX_FRAMES:
        raise DrawingError(f"frames must be in [2, {MAX_FRAMES}] for an animation, got {frames}")
    period = cycle(scenario)
    per_frame = max(1, math.ceil(scenario.steps * period / scenario.t_end / frames - 1e-9))
    return np.linspace(0.0, period, frames * per_frame + 1), [k * per_frame for k in range(frames)]


def solve(scenario: Scenario, times: np.ndarray) -> Trajectory:
    """Every body's trajectory on `times` by the native solver; DrawingError if it fails."""
    engine = adapters.load(adapters.NATIVE)
    result = engine.run(consistent_start(scenario), native_setting(scenario), times)
    if result.status != "ok" or result.trajectory is None:
        raise DrawingError(
            f"the native solver could not pose {scenario.name}: {result.status}: {result.message}"
        )
    return result.trajectory


def instants(scenario: Scenario, trajectory: Trajectory, indices: list[int]) -> list[Instant]:
    """The drawing's shapes at the trajectory's rows `indices`."""
    if trajectory.position is None:
        raise DrawingError(f"the trajectory of {scenario.name} has no positions")
    found = []
    for k in indices:
        poses = {
            b: tuple(float(v) for v in trajectory.position[k, i]) for i, b in enumerate(trajectory.bodies)
        }
        extras = {name: float(values[k]) for name, values in trajectory.extras.items()}
        found.append(instant(scenario, float(trajectory.times[k]), poses, extras))  # type: ignore[arg-type]
    return found


def draw_svg(scenario: Scenario, t: float = 0.0, frames: int = 1) -> str:
    """The mechanism of `scenario` at time `t` (frames = 1), or one cycle in `frames` frames
    (2 to MAX_FRAMES, `t` unused) looping in a browser, as the text of one SVG file."""
    if frames == 1:
        times = still_grid(scenario, t)
        index = 0 if t == 0.0 else len(times) - 1
        return svg_document(scenario, instants(scenario, solve(scenario, times), [index]))
    times, indices = frame_grid(scenario, frames)
    return svg_document(scenario, instants(scenario, solve(scenario, times), indices))


def _scale_bar(view: View) -> str:
    """A bar of a round length (1, 2 or 5 times a power of ten) near a fifth of the width."""
    target = 0.2 * (view.width - 2 * MARGIN) / view.scale
    power = 10.0 ** math.floor(math.log10(target))
    length = max(m * power for m in (1.0, 2.0, 5.0) if m * power <= target)
    x0, y = MARGIN / 2, view.height - BOTTOM / 2
    x1 = x0 + length * view.scale
    return (
        f'<g class="scalebar"><title>scale: {length:g} m</title>'
        f'<path class="scale" d="M{num(x0)},{num(y - 5)} V{num(y)} H{num(x1)} V{num(y - 5)}"/>'
        f'<text class="label" x="{num(x1 + 6)}" y="{num(y + 4)}">{length:g} m</text></g>'
    )


def _frames(found: list[Instant], view: View, bodies: tuple[str, ...]) -> list[str]:
    """Each instant as a group; several loop by SMIL, each shown for its share of the cycle."""
    if len(found) == 1:
        return [f'<g class="frame" data-t="{found[0].t!r}">{frame(found[0], view, bodies)}</g>']
    n = len(found)
    duration = min(max(SECONDS_PER_FRAME * n, 2.0), 8.0)
    groups = []
    for k, item in enumerate(found):
        values = ["hidden"] * n
        values[k] = "visible"
        animate = (
            f'<animate attributeName="visibility" dur="{duration:g}s" repeatCount="indefinite" '
            f'calcMode="discrete" values="{";".join(values)}" '
            f'keyTimes="{";".join(num(j / n) for j in range(n))}"/>'
        )
        clock = f'<text class="sub" x="{num(view.width - MARGIN * 2.5)}" y="38">t = {item.t:.4g} s</text>'
        visible = "visible" if k == 0 else "hidden"
        groups.append(
            f'<g class="frame" data-t="{item.t!r}" visibility="{visible}">{animate}{clock}\n'
            f"{frame(item, view, bodies)}</g>"
        )
    return groups


def svg_document(scenario: Scenario, found: list[Instant]) -> str:
    """The SVG of the instants: one still, or an animation of several over the cycle they span."""
    view = fit(found, scenario.characteristic_length)
    bodies = scenario.body_names
    if len(found) == 1:
        heading = f"{scenario.name} at t = {found[0].t:.6g} s"
    else:
        heading = f"{scenario.name}: one cycle ({cycle(scenario):.6g} s) in {len(found)} frames"
    description = escape(scenario.description) if scenario.description else ""
    ids = "mbx-" + hashlib.sha1(f"{scenario.name} {heading} {found[0].t!r}".encode()).hexdigest()[:10]
    head = (
        f'<svg xmlns="http://www.w3.org/2000/svg" class="{SCOPE}" '
        f'width="{num(view.width)}" height="{num(view.height)}" '
        f'viewBox="0 0 {num(view.width)} {num(view.height)}" data-scale="{view.scale!r}" '
        f'data-origin-x="{view.ox!r}" data-origin-y="{view.oy!r}">'
    )
    text = "\n".join(
        [
            head,
            f"<title>{escape(heading)}</title>",
            f"<style>{scoped_style(ids)}</style>",
            DEFS,
            '<rect width="100%" height="100%" fill="#fff"/>',
            f'<text class="title" x="{num(MARGIN / 2)}" y="22">{escape(heading)}</text>',
            f'<text class="sub" x="{num(MARGIN / 2)}" y="38">{description}</text>',
            *_frames(found, view, bodies),
            _scale_bar(view),
            "</svg>",
            "",
        ]
    )
    return unique_ids(text, ids)
