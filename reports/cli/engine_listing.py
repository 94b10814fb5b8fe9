"""One engine's declared facts for `mbxval list --engine NAME`: its modes, its options (type, range,
help) and its accuracy knobs (adapters.knobs), one line each as text, or as Markdown tables (the
sections of docs/engine-knobs.md: reports.cli.knobs_page)."""

from __future__ import annotations

import adapters
from adapters.base import Adapter

FORMATS = ("text", "markdown")


def engine_text(kind: type[Adapter]) -> list[str]:
    """`kind`'s modes, options and knobs, one line each."""
    lines = [f"engine {kind.name}", "modes:"]
    lines += [f"  {mode.name}: {mode.measures}" for mode in kind.measured]
    lines += [f"  {name}" for name in kind.modes if not kind.measured]
    lines.append("options:")
    lines += [f"  {o.name}: {o.describe()}{': ' + o.help if o.help else ''}" for o in kind.options]
    lines.append("knobs:")
    lines += [f"  {knob.name}: {knob.treatment}: {knob.why}" for knob in kind.knobs]
    return lines


def engine_markdown(kind: type[Adapter]) -> list[str]:
    """`kind`'s modes, options and knobs as a Markdown section of three tables."""
    lines = [f"## {kind.name}", "", "| mode | measures |", "| --- | --- |"]
    lines += [f"| {_cell(m.name)} | {_cell(m.measures)} |" for m in kind.measured]
    lines += [f"| {_cell(name)} | |" for name in kind.modes if not kind.measured]
    lines += ["", "| option | type and range | help |", "| --- | --- | --- |"]
    lines += [f"| `{o.name}` | {_cell(o.describe())} | {_cell(o.help)} |" for o in kind.options]
    lines += ["", "| knob | treatment | why |", "| --- | --- | --- |"]
    lines += [f"| {_cell(k.name)} | {k.treatment} | {_cell(k.why)} |" for k in kind.knobs]
    return [*lines, ""]


def engine_listing(name: str, form: str) -> str:
    """Engine `name`'s listing in `form` (FORMATS); EngineUnavailable for an unknown or missing one."""
    kind = adapters.adapter_class(name)
    lines = engine_text(kind) if form == "text" else engine_markdown(kind)
    return "\n".join(lines).rstrip("\n") + "\n"


def _cell(text: str) -> str:
    """`text` safe inside a Markdown table cell."""
    return text.replace("|", "\\|").replace("\n", " ")
