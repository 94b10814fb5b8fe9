"""Text the report did not write, made safe where it lands: every page builder passes names,
labels, engine names, messages and settings through here (one boundary), never writes them raw.

- HTML text and attribute values: `escape` (html.escape with quotes);
- ids and the links to them: `anchor`, a slug of safe characters only, the same for both;
- Markdown text, cells and headings: `markdown_text` (HTML, Markdown's active characters and line
  breaks escaped); a value shown as code: `markdown_code` (a code span no backtick closes);
- figure text (titles, legends): `figure_text` (a `$` would start matplotlib's mathtext).
"""

from __future__ import annotations

import html
import re

SAFE = frozenset("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.")


def escape(value: object) -> str:
    """`value` as HTML text or a quoted attribute's value."""
    return html.escape(str(value), quote=True)


def anchor(scenario: str) -> str:
    """The id of a scenario's section: `s-` then its name with `/` as `-`, every character outside
    ASCII letters, digits and `_-.` as `~` and its code point in hex (no quote, space or markup)."""
    return "s-" + "".join(c if c in SAFE else "-" if c == "/" else f"~{ord(c):x}" for c in scenario)


MARKDOWN_ACTIVE = re.compile(r"([\\`*\[\]|~!])")
"""What Markdown acts on inside a line: the backslash itself, a code span's backtick, emphasis and
strikethrough, a link's or image's brackets, a table's pipe. (`_` is left as written: GitHub's
Markdown reads it literally inside a word, as in every scenario name, and escaping it would change
every name's text in the file; HTML's `<` and `&` are escaped as HTML.)"""


def markdown_text(value: object) -> str:
    """`value` as Markdown text: HTML escaped (Markdown renderers pass raw HTML through), every
    MARKDOWN_ACTIVE character backslash-escaped (a backtick opens no code span, a pipe splits no
    cell), line breaks as spaces (a heading or cell is one line)."""
    text = MARKDOWN_ACTIVE.sub(r"\\\1", html.escape(str(value), quote=False))
    return " ".join(text.splitlines())


def markdown_code(value: object) -> str:
    """`value` as a Markdown code span, shown as written: fenced by one backtick more than its
    longest run of backticks (so none inside closes it), padded where it starts or ends with one;
    line breaks as spaces."""
    text = " ".join(str(value).splitlines())
    fence = "`" * (max((len(run) for run in re.findall("`+", text)), default=0) + 1)
    pad = " " if text.startswith("`") or text.endswith("`") else ""
    return f"{fence}{pad}{text}{pad}{fence}"


def figure_text(value: object) -> str:
    """`value` as matplotlib text, shown as written: `$` escaped, so no mathtext is parsed."""
    return str(value).replace("$", "\\$")
