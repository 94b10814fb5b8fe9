"""Text the report did not write, made safe where it lands: every page builder passes names,
labels, engine names, messages and settings through here (one boundary), never writes them raw.

- HTML text and attribute values: `escape` (html.escape with quotes);
- ids and the links to them: `anchor`, a slug of safe characters only, the same for both;
- Markdown cells and headings: `markdown_text` (HTML, pipes and line breaks escaped);
- figure text (titles, legends): `figure_text` (a `$` would start matplotlib's mathtext).
"""

from __future__ import annotations

import html

SAFE = frozenset("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.")


def escape(value: object) -> str:
    """`value` as HTML text or a quoted attribute's value."""
    return html.escape(str(value), quote=True)


def anchor(scenario: str) -> str:
    """The id of a scenario's section: `s-` then its name with `/` as `-`, every character outside
    ASCII letters, digits and `_-.` as `~` and its code point in hex (no quote, space or markup)."""
    return "s-" + "".join(c if c in SAFE else "-" if c == "/" else f"~{ord(c):x}" for c in scenario)


def markdown_text(value: object) -> str:
    """`value` as Markdown text: HTML escaped (Markdown renderers pass raw HTML through), pipes
    escaped (a table cell), line breaks as spaces (a heading or cell is one line)."""
    text = html.escape(str(value), quote=False).replace("|", "\\|")
    return " ".join(text.splitlines())


def figure_text(value: object) -> str:
    """`value` as matplotlib text, shown as written: `$` escaped, so no mathtext is parsed."""
    return str(value).replace("$", "\\$")
