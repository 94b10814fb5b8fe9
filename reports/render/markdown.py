"""The Markdown summary: provenance, the status matrix and each scenario's table of runs."""

from __future__ import annotations

import reports.render.engine_reach as engine_reach
import reports.render.stability_render as stability_render
import reports.render.sweep_render as sweep_render
from reports.render.first_screen import native_line, scenario_rate, truth_names
from reports.render.markdown_table import markdown_table
from reports.render.markup import markdown_code, markdown_text
from reports.render.report_data import HEADINGS, ReportData, number, revision_label, table, timing_note
from reports.store import LEVEL_COLUMNS, SCALE_DEFINITION

SHOWN = ("engine", "setting", "status", *LEVEL_COLUMNS.values(), "constraint_residual", "run_time", "message")
SUMMARY_COLUMNS = tuple(HEADINGS.get(c, c) for c in SHOWN)


def render(data: ReportData) -> str:
    """The summary; the points of parameter sweeps as one table per sweep, not scenario by scenario."""
    meta, whole, data = data.meta, data, data.unswept()
    engines = ", ".join(f"{k} {v}" for k, v in meta.get("engines", {}).items())
    machine = meta.get("machine", {})
    machine = machine if isinstance(machine, dict) else {}
    text = markdown_text  # every stored value passes through it (or markdown_code): none is trusted
    lines = [
        "# mbxval report",
        "",
        f"Suite {markdown_code(meta.get('suite', '?'))}, {text(meta.get('date', '?'))}, "
        f"git {markdown_code(revision_label(meta))}.",
        f"Engines: {text(engines)}. Python {text(meta.get('python', '?'))}; "
        f"{text(machine.get('processor', '?'))}, {text(machine.get('cpus', '?'))} CPUs.",
        f"Timing: minimum of up to {text(meta.get('repeats', '?'))} repeats "
        f"after {text(meta.get('warmup', '?'))} warm-up.",
        "",
        f"{text(meta.get('scales', SCALE_DEFINITION))} The truth: {text(meta.get('truth', ''))}.",
        "",
        text(timing_note(whole.frame)),
    ]
    if not data.frame.empty:
        lines[-4:-4] = [f"**{text(native_line(data.frame, data.native_engine()))}**", ""]
        lines += [
            "",
            "## Status and error (position / velocity / acceleration) at each engine's default setting",
            "",
            markdown_table(data.matrix(), "scenario"),
            "",
            "Runs by status: " + text(", ".join(f"{s} {n}" for s, n in data.status_counts().items())) + ".",
            "",
            "## Each engine out of the box, and at its best",
            "",
            *engine_reach.markdown_lines(data.frame, markdown_text),
        ]
    swept = sweep_render.markdown_section(whole)  # "" unless the results hold parameter sweeps
    if swept:
        lines += ["", swept.rstrip("\n")]
    stability = stability_render.markdown_section(data)  # "" unless the results hold stress cases
    if stability:
        lines += ["", stability.rstrip("\n")]
    for scenario in data.scenarios():
        rows = table(data.rows(scenario))[list(SUMMARY_COLUMNS)]
        lines += [
            "",
            f"## {markdown_text(scenario)}",
            "",
            f"Truth: {markdown_text(truth_names(data.rows(scenario)))}. "
            f"Characteristic length {text(number(data.characteristic_length(scenario)))} m, "
            f"rate {text(number(scenario_rate(data, scenario)))} rad/s.",
            "",
            markdown_table(rows),
            "",
            text(timing_note(data.rows(scenario))),
        ]
    return "\n".join(lines) + "\n"
