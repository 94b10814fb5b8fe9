"""The self-contained HTML report: everything inline (CSS, base64 PNG plots), no network needed.

Up front: provenance, engine versions, the headline definition and the scenario x engine matrix of
status and error at the default setting. Then one section per scenario: work-precision plot,
trajectory overlays, error over time and the table of runs.
"""

from __future__ import annotations

import html
from typing import Any

from reports.render import plots, stability_render
from reports.render.report_data import ReportData, cell_text, number, table

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
img { max-width: 100%; margin: 0.3em 0; } .muted { color: #666; font-size: 0.9em; }
.wide { overflow-x: auto; }
.plots { display: flex; flex-wrap: wrap; gap: 1em; align-items: flex-start; }
"""

# Lets a headless browser (scripts/check_report_in_browser.sh) confirm every plot decoded.
CHECK = """
window.addEventListener('load', function () {
  var images = document.querySelectorAll('img.plot');
  var good = Array.prototype.filter.call(images, function (i) { return i.complete && i.naturalWidth > 0; });
  document.body.setAttribute('data-plots-loaded', good.length + '/' + images.length);
});
"""


def render(data: ReportData) -> str:
    """The whole page as text."""
    meta = data.meta
    parts = [
        "<!DOCTYPE html>",
        '<html lang="en"><head><meta charset="utf-8">',
        "<title>mbxval report</title>",
        f"<style>{STYLE}</style><script>{CHECK}</script></head><body>",
        "<h1>mbxval: planar multibody kinematics across engines</h1>",
        f'<p class="muted">{html.escape(_provenance(meta))}</p>',
        "<h2>Status and error at each engine's default setting</h2>",
        f"<p>{html.escape(_definitions(meta))}</p>",
        _matrix(data),
        f'<p class="muted">Runs by status: {html.escape(_counts(data))}.</p>',
        stability_render.html_fragment(data),  # "" unless the results hold stress cases
        "<h2>Engines and machine</h2>",
        _key_values(_versions(meta)),
    ]
    for scenario in data.scenarios():
        parts.append(_scenario_section(data, scenario))
    parts.append("</body></html>")
    return "\n".join(parts)


def _definitions(meta: dict[str, Any]) -> str:
    return f"{meta.get('headline', '')} The truth: {meta.get('truth', '')}."


def _provenance(meta: dict[str, Any]) -> str:
    revision = str(meta.get("git_revision", "?"))[:12]
    return (
        f"suite {meta.get('suite', '?')}, {meta.get('date', '?')}, git {revision}, "
        f"timing: minimum of {meta.get('repeats', '?')} repeats after {meta.get('warmup', '?')} warm-up, "
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
    rows = "".join(f"<tr><th>{html.escape(k)}</th><td>{html.escape(v)}</td></tr>" for k, v in values.items())
    return f"<table>{rows}</table>"


def _counts(data: ReportData) -> str:
    return ", ".join(f"{status} {count}" for status, count in data.status_counts().items())


def _matrix(data: ReportData) -> str:
    head = "".join(f"<th>{html.escape(e)}</th>" for e in data.engines())
    body = []
    for scenario in data.scenarios():
        cells = []
        for engine in data.engines():
            row = data.default_row(scenario, engine)
            css = "notrun" if row is None else str(row["status"])
            tip = "" if row is None else f"{row['setting']}: {row['message']}".strip(": ")
            cells.append(f'<td class="{css}" title="{html.escape(tip)}">{html.escape(cell_text(row))}</td>')
        link = f'<a href="#{_anchor(scenario)}">{html.escape(scenario)}</a>'
        body.append(f"<tr><th>{link}</th>{''.join(cells)}</tr>")
    return f"<table><tr><th>scenario</th>{head}</tr>{''.join(body)}</table>"


def _anchor(scenario: str) -> str:
    return "s-" + scenario.replace("/", "-")


def _image(figure: Any, alt: str) -> str:
    if figure is None:
        return f'<p class="muted">no {html.escape(alt)}: no successful run to draw</p>'
    return f'<img class="plot" alt="{html.escape(alt)}" src="data:image/png;base64,{plots.png(figure)}">'


def _scenario_section(data: ReportData, scenario: str) -> str:
    rows = data.rows(scenario)
    length = data.characteristic_length(scenario)
    truth = data.truth(scenario)
    runs = data.default_trajectories(scenario)
    figures = [_image(plots.work_precision(rows), "work-precision plot")]
    if truth is not None:
        figures.append(_image(plots.error_over_time(truth, runs, length), "error over time"))
        overlay = _image(plots.overlays(truth, runs, length), "trajectory overlay")
    else:
        overlay = '<p class="muted">no stored truth trajectory: no overlays</p>'
    shown = table(rows)
    return "\n".join(
        [
            f'<h2 id="{_anchor(scenario)}">{html.escape(scenario)}</h2>',
            f'<p class="muted">characteristic length {number(length)} m; '
            f"{int(rows['grid_points'].iloc[0])} grid points over {number(rows['t_end'].iloc[0])} s</p>",
            f'<div class="plots">{"".join(figures)}</div>',
            overlay,
            f'<div class="wide">{shown.to_html(index=False, escape=True, border=0)}</div>',
        ]
    )
