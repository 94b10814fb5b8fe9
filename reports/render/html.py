"""The self-contained HTML report: everything inline (CSS, SVG plots), no network needed.

Up front (reports.render.first_screen): the native solver's agreement with the closed forms in one
line, the scenario x engine matrix at every level, the error against run time over the whole suite
per engine and mode, and the engines' agreement with each other. Then the stability map (stress suite
only), engines and machine, and one section per scenario: work-precision and deviation from the truth
at the three levels side by side, and the table of runs.
"""

from __future__ import annotations

import base64
import contextlib
import html as html_module
import multiprocessing
import os
import re
from collections.abc import Callable, Iterator
from typing import Any

import reports.render.dynamics_render as dynamics_render
import reports.render.engine_reach as engine_reach
import reports.render.first_screen as first_screen
import reports.render.level_plots as level_plots
import reports.render.markup as markup
import reports.render.overview as overview
import reports.render.stability_render as stability_render
import reports.render.svg_figure as svg_figure
import reports.render.sweep_render as sweep_render
from reports.render.clock import clock_label
from reports.render.report_data import (
    DRIFT_MARK,
    ReportData,
    map_cell_rows,
    number,
    revision_label,
    table,
    timing_note,
)
from reports.store import ERROR_SERIES, FORCE_DEFINITION, NOT_RECORDED, SCALE_DEFINITION

STYLE = """
body { font-family: system-ui, sans-serif; margin: 1.5em auto; max-width: 1200px; color: #222; }
h1 { margin-bottom: 0.2em; } h2 { border-bottom: 1px solid #ccc; margin-top: 2em; }
table { border-collapse: collapse; font-size: 0.85em; margin: 0.5em 0; }
th, td { border: 1px solid #ccc; padding: 0.2em 0.5em; text-align: left; vertical-align: top; }
th { background: #f3f3f3; } td { white-space: nowrap; }
td:nth-child(2) { white-space: normal; min-width: 16em; }
td:last-child { white-space: normal; max-width: 30em; overflow-wrap: anywhere; }
td.ok { background: #e6f4e6; } td.unsupported { background: #eeeeee; color: #666; }
td.failed, td.diverged, td.singular, td.timeout { background: #fbe3e3; }
td.notrun { color: #999; }
img, svg.plot { max-width: 100%; height: auto; margin: 0.3em 0; } .muted { color: #666; font-size: 0.9em; }
.wide { overflow-x: auto; }
table.matrix td { min-width: 0; white-space: nowrap; padding: 0.15em 0.35em; }
table.matrix .force { border-left: 2px solid #557; font-style: italic; }
.plots { display: flex; flex-wrap: wrap; gap: 1em; align-items: flex-start; }
figure.drawing { margin: 0.5em 0; } img.drawing { max-height: 460px; max-width: 100%; width: auto; }
"""

WORKERS = 2
_FORKED: dict[str, ReportData] = {}

# Lets a headless browser (scripts/check_report_in_browser.sh) confirm every plot decoded.
CHECK = """
window.addEventListener('load', function () {
  var images = document.querySelectorAll('img.plot, svg.plot');
  var good = Array.prototype.filter.call(images, function (i) {
    return i.tagName === 'IMG' ? i.complete && i.naturalWidth > 0 : i.getBoundingClientRect().width > 0;
  });
  document.body.setAttribute('data-plots-loaded', good.length + '/' + images.length);
});
"""

_TITLE = re.compile(r"<title>([^<]*)</title>")
"""A drawing's first title: what it shows (a still at t, or a cycle in frames)."""


def render(data: ReportData) -> str:
    """The whole page as text. The points of parameter sweeps are drawn as maps up front (a first
    screen of their own) and left out of the per-scenario matrix and sections."""
    meta, whole, data = data.meta, data, data.unswept()
    listed = data.without(map_cell_rows(data.frame)["scenario"])  # drawn as the dynamics map
    with _sections_drawn(listed) as sections:  # drawn by forked workers while this process draws the rest
        return "\n".join([*_page(meta, whole, data, listed), *sections(), "</body></html>"])


def _page(meta: dict[str, Any], whole: ReportData, data: ReportData, listed: ReportData) -> list[str]:
    """The page up to the scenarios' sections: what `render` draws in this process."""
    dynamics = dynamics_render.html_fragment(data, _image)  # "" without dynamic scenarios
    parts = [
        "<!DOCTYPE html>",
        '<html lang="en"><head><meta charset="utf-8">',
        "<title>mbxval report</title>",
        f"<style>{STYLE}</style><script>{CHECK}</script></head><body>",
        f"<h1>mbxval: planar multibody {_subject(meta)} across engines</h1>",
        f'<p class="muted">{markup.escape(_provenance(meta))}</p>',
        sweep_render.html_fragment(whole),  # "" unless the results hold parameter sweeps
    ]
    if not data.frame.empty:
        parts += [
            f"<p><strong>{markup.escape(_headline(data))}</strong></p>",
            "<h2>Error at each level, each engine's default setting</h2>",
            f'<p class="muted">{markup.escape(_definitions(meta))}</p>',
            first_screen.level_matrix(listed),
            f'<p class="muted">Runs by status: {markup.escape(_counts(data))}. Colour: log10 error from '
            f"1e{first_screen.BEST:.0f} (green) to 1e{first_screen.WORST:.0f} (red); hover a scenario for "
            f"its truth. {DRIFT_MARK.strip()}: the run ended ok but its own figures say it "
            "drifted (a constraint residual above 1e-3, an energy balance, T + V against the work of its "
            "loads and drivers, off by more than 1e-2 of its energy scale, or positions moved by more than "
            "1e-2 at half the step where no truth judges it), found without any truth; hover the cell for "
            "the figure.</p>",
            "<h2>Each engine out of the box, and at its best</h2>",
            engine_reach.html_table(listed.frame, markup.escape),
            f'<p class="muted">{markup.escape(REACH_NOTE)}</p>',
            dynamics,
        ]
    parts += [
        "<h2>Error against run time over the suite</h2>",
        _overview(whole),
        f'<p class="muted">{markup.escape(timing_note(whole.frame))}</p>',
    ]
    if not data.frame.empty:
        parts += [
            "<h2>Engines against each other (default settings)</h2>",
            _agreement(listed),
            stability_render.html_fragment(data),  # "" unless these are the stress suite's results
        ]
    parts += ["<h2>Engines and machine</h2>", _key_values(_versions(meta)), _modes(whole)]
    return parts


REACH_NOTE = (
    "Untuned: each engine with its own defaults as a new user's model gets them, at the rule's step "
    "(engines with no separate defaults declare none). Its default: the setting its settings rule "
    "gives (docs/settings-rule.md). At its best: per scenario the smallest error, over the levels it "
    "produces, of any setting it was run at; the column gives the worst scenario's, and the median run "
    f"time of those best settings. The cost of {engine_reach.TARGET:g}: per scenario the least run time "
    "among the settings that meet it at every level, read off the work-precision front."
)


def _headline(data: ReportData) -> str:
    if data.meta.get("suite") == "dynamics":
        return dynamics_render.headline(data)
    return first_screen.native_line(data.frame, data.native_engine())


def _subject(meta: dict[str, Any]) -> str:
    return "dynamics" if meta.get("suite") == "dynamics" else "kinematics"


def _definitions(meta: dict[str, Any]) -> str:
    scales = meta.get("scales", SCALE_DEFINITION)
    return (
        f"{scales} The truth: {meta.get('truth', '')}. The force column: {FORCE_DEFINITION}; its truth "
        "is always the native solver's (inverse dynamics in a driven scenario, the dynamic truth's "
        "multipliers in free dynamics)."
    )


def _provenance(meta: dict[str, Any]) -> str:
    revision = revision_label(meta)
    return (
        f"suite {meta.get('suite', '?')}, {meta.get('date', '?')}, git {revision}, "
        f"timing: minimum of up to {meta.get('repeats', '?')} repeats "
        f"after {meta.get('warmup', '?')} warm-up, "
        f"time limit {meta.get('timeout', '?')} s per run"
    )


def _versions(meta: dict[str, Any]) -> dict[str, str]:
    machine = meta.get("machine", {})
    info = {f"engine {k}": str(v) for k, v in meta.get("engines", {}).items()}
    info.update({f"package {k}": str(v) for k, v in meta.get("packages", {}).items()})
    info["python"] = str(meta.get("python", "?"))
    info["machine"] = ", ".join(f"{k} {v}" for k, v in machine.items())
    return info


def _key_values(values: dict[str, str]) -> str:
    rows = "".join(
        f"<tr><th>{markup.escape(k)}</th><td>{markup.escape(v)}</td></tr>" for k, v in values.items()
    )
    return f"<table>{rows}</table>"


def _modes(data: ReportData) -> str:
    """What each engine mode in the results measures (the rows' `measures` column)."""
    if "measures" not in data.frame:
        return ""
    known = data.frame[data.frame["measures"].astype(str) != ""]
    modes = known.drop_duplicates(["engine", "mode"])[["engine", "mode", "measures"]]
    if modes.empty:
        return ""
    order = {engine: k for k, engine in enumerate(data.engines())}
    modes = (
        modes.assign(_order=modes["engine"].map(order)).sort_values(["_order", "mode"]).drop(columns="_order")
    )
    note = (
        "What each mode measures: the engine's own solver or integrator, or a loop in the adapter on "
        "the engine's kinematics, and which levels the adapter derives."
    )
    return f'<p class="muted">{note}</p>{modes.to_html(index=False, escape=True, border=0)}'


def _counts(data: ReportData) -> str:
    return ", ".join(f"{status} {count}" for status, count in data.status_counts().items())


def _overview(data: ReportData) -> str:
    summary = overview.summary(data.frame, float(data.meta.get("timeout", float("nan"))))
    truths = first_screen.truth_names(data.frame)
    clock = clock_label(data.frame)
    figure = overview.overview_figure(summary, truths, clock) if not summary.empty else None
    return _image(figure, "overview of error against run time", _why_none(data.frame)) + _muted(
        " ".join(filter(None, (overview.untimed_note(data.frame), overview.DEFINITION)))
    )


def _why_none(rows: Any) -> str:
    """Why a figure of error against run time has nothing to draw."""
    return "no timed run to draw" if overview.untimed(rows).any() else "no successful run to draw"


def _muted(text: str) -> str:
    return f'<p class="muted">{markup.escape(text)}</p>'


def _agreement(data: ReportData) -> str:
    frame = first_screen.agreement_frame(data)
    if frame.empty:
        return '<p class="muted">no scenario has default runs of two engines to compare</p>'
    note = (
        "Per scenario and level, the pair of engines whose default runs differ most and by how much "
        "(dimensionless, as above; no truth involved)."
    )
    shown = frame.to_html(index=False, escape=True, border=0)
    return f'<p class="muted">{note}</p><div class="wide">{shown}</div>'


def _image(figure: Any, alt: str, why: str = "no successful run to draw") -> str:
    """The figure inline (drawn with its own fixed margins), or why there is none."""
    if figure is None:
        return _muted(f"no {alt}: {why}")
    return svg_figure.svg(figure, alt)


@contextlib.contextmanager
def _sections_drawn(data: ReportData) -> Iterator[Callable[[], list[str]]]:
    """Every scenario's section, drawn by up to WORKERS forked processes (the figures are most of a
    report's render time, and each scenario's are independent of the others'), started on entry so
    that this process draws the rest of the page meanwhile (the dynamics figures among it, a third
    of a dynamics report's render); yields the function that waits for the sections, in order."""
    names = data.scenarios()
    workers = min(WORKERS, os.cpu_count() or 1, len(names))
    if workers <= 1 or "fork" not in multiprocessing.get_all_start_methods():
        yield lambda: [_scenario_section(data, name) for name in names]
        return
    _FORKED["data"] = data  # inherited by the forked workers, never pickled
    try:
        with multiprocessing.get_context("fork").Pool(workers) as pool:
            pending = pool.map_async(_forked_section, names, chunksize=1)
            yield pending.get
    finally:
        _FORKED.clear()


def _forked_section(scenario: str) -> str:
    return _scenario_section(_FORKED["data"], scenario)


def _drawing(data: ReportData, scenario: str) -> str:
    """The mechanism as the run drew it (reports.drawing: one cycle animated, or the still at
    t = 0), or nothing. Embedded as an image, never as markup: a results directory may come from
    anywhere, and an image runs no script. Its alternative text is the drawing's own title."""
    svg = data.drawings.get(scenario, "")
    if not svg.lstrip().startswith("<svg"):
        return ""
    source = "data:image/svg+xml;base64," + base64.b64encode(svg.encode("utf-8")).decode("ascii")
    found = _TITLE.search(svg)
    alt = html_module.unescape(found.group(1)) if found else f"the mechanism of {scenario}"
    caption = "posed by the native solver; `mbxval draw` draws any t or number of frames"
    return (
        f'<figure class="drawing"><img class="drawing" src="{source}" alt="{markup.escape(alt)}">'
        f'<figcaption class="muted">{markup.escape(caption)}</figcaption></figure>'
    )


def _scenario_section(data: ReportData, scenario: str) -> str:
    rows = data.rows(scenario)
    length, rate = data.characteristic_length(scenario), first_screen.scenario_rate(data, scenario)
    truth, truth_name = data.truth(scenario), first_screen.truth_names(rows)
    figures = [_image(level_plots.work_precision(rows, truth_name), "work-precision plot", _why_none(rows))]
    if truth is not None:
        runs = data.default_trajectories(scenario)
        stored = any(name in run.extras for run in runs.values() for name in ERROR_SERIES.values())
        why = NOT_RECORDED if runs and not stored else "no successful run to draw"
        figures.append(_image(level_plots.deviations(truth, runs, truth_name), "deviations", why))
    else:
        figures.append('<p class="muted">no stored truth trajectory: no deviations</p>')
    shown = table(rows)
    return "\n".join(
        [
            f'<h2 id="{markup.anchor(scenario)}">{markup.escape(scenario)}</h2>',
            f'<p class="muted">truth: {markup.escape(truth_name)}; characteristic length {number(length)} m, '
            f"characteristic rate {number(rate)} rad/s; "
            f"{int(rows['grid_points'].iloc[0])} grid points over {number(rows['t_end'].iloc[0])} s</p>",
            _drawing(data, scenario),
            f'<div class="plots">{"".join(figures)}</div>',
            f'<p class="muted">{markup.escape(timing_note(rows))}</p>',
            f'<div class="wide">{shown.to_html(index=False, escape=True, border=0)}</div>',
        ]
    )
